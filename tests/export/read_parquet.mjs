// Reads a Parquet file with hyparquet, a reader independent of comply's writer, and prints what
// the cross-check tests compare as one JSON object: the footer (rows, row groups, the leaf
// columns' paths and physical types, the key/value metadata) and every row. INT64 values are
// printed as decimal strings (JSON numbers would round them past 2^53).
//
//   node tests/export/read_parquet.mjs FILE.parquet
import { asyncBufferFromFile, parquetMetadataAsync, parquetReadObjects } from './node/node_modules/hyparquet/src/node.js';

const path = process.argv[2];
if (!path) {
  console.error('usage: read_parquet.mjs FILE.parquet');
  process.exit(2);
}
const file = await asyncBufferFromFile(path);
const metadata = await parquetMetadataAsync(file);
const rows = await parquetReadObjects({ file });
const plain = (value) => {
  if (typeof value === 'bigint') return value.toString();
  if (Array.isArray(value)) return value.map(plain);
  return value;
};
const leaves = metadata.schema.filter((element) => element.type !== undefined)
  .map((element) => ({ name: element.name, type: element.type }));
console.log(JSON.stringify({
  num_rows: Number(metadata.num_rows),
  row_groups: metadata.row_groups.map((group) => Number(group.num_rows)),
  leaves,
  key_value_metadata: Object.fromEntries((metadata.key_value_metadata ?? []).map((kv) => [kv.key, kv.value])),
  created_by: metadata.created_by,
  rows: rows.map((row) => Object.fromEntries(Object.entries(row).map(([k, v]) => [k, plain(v)]))),
}));
