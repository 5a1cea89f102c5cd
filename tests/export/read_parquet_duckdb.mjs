// Reads a Parquet file with DuckDB, a second reader independent of comply's writer (and of
// hyparquet, tests/export/read_parquet.mjs), and prints its row count and every row as one JSON
// object. INT64 values are printed as decimal strings, lists as arrays.
//
//   node tests/export/read_parquet_duckdb.mjs FILE.parquet
import { DuckDBInstance } from './node/node_modules/@duckdb/node-api/lib/index.js';

const path = process.argv[2];
if (!path) {
  console.error('usage: read_parquet_duckdb.mjs FILE.parquet');
  process.exit(2);
}
const instance = await DuckDBInstance.create(':memory:');
const connection = await instance.connect();
const quoted = `'${path.replaceAll("'", "''")}'`;
const count = await connection.runAndReadAll(`SELECT count(*) AS n FROM read_parquet(${quoted})`);
const reader = await connection.runAndReadAll(`SELECT * FROM read_parquet(${quoted})`);
const columns = await connection.runAndReadAll(
  `SELECT name, type FROM parquet_schema(${quoted}) WHERE num_children IS NULL OR num_children = 0`);
console.log(JSON.stringify({
  num_rows: Number(count.getRowObjectsJson()[0].n),
  leaves: columns.getRowObjectsJson(),
  rows: reader.getRowObjectsJson(),
}));
