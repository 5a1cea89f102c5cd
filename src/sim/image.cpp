// PNG files through libpng, which reports errors by longjmp: every function that calls setjmp
// below holds only trivially destructible locals, so a longjmp never skips a destructor; the
// C++ objects (file handle, libpng structs, row buffers) live one frame up and are released
// normally after the error is turned into a SimError.

#include "comply/sim/image.hpp"

#include <png.h>

#include <algorithm>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <string>

#include "comply/sim/sim_error.hpp"

namespace comply::sim {
namespace {

std::size_t byteCount(int width, int height) {
  return static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3;
}

std::string quoted(const std::filesystem::path& file) {
  return "'" + file.string() + "'";
}

void checkLayout(const Image& image, const char* where) {
  if (image.width < 0 || image.height < 0 ||
      image.rgb.size() != byteCount(image.width, image.height)) {
    throw SimError(std::string(where) + ": image of " + std::to_string(image.width) + " x " +
                   std::to_string(image.height) + " pixels holds " +
                   std::to_string(image.rgb.size()) + " bytes, expected width * height * 3");
  }
}

/// Where libpng's error callback leaves its message for the code that turns it into a SimError.
struct PngError {
  char message[256] = "unknown libpng error";
};

[[noreturn]] void onPngError(png_structp png, png_const_charp message) {
  auto* error = static_cast<PngError*>(png_get_error_ptr(png));
  std::snprintf(error->message, sizeof error->message, "%s", message);
  png_longjmp(png, 1);
}

// Warnings (e.g. an unknown ancillary chunk) do not stop reading or writing; stderr is not ours.
void onPngWarning(png_structp, png_const_charp) {}

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using FileHandle = std::unique_ptr<std::FILE, FileCloser>;

FileHandle openFile(const std::filesystem::path& file, const char* mode, const char* where) {
  std::FILE* handle = std::fopen(file.c_str(), mode);
  if (handle == nullptr) {
    throw SimError(std::string(where) + ": cannot open " + quoted(file) + ": " +
                   std::strerror(errno));
  }
  return FileHandle(handle);
}

/// libpng's state for one file, either direction: libpng keeps separate create and destroy calls
/// for reading and writing.
template <bool kWriting>
struct PngHandle {
  png_structp png = nullptr;
  png_infop info = nullptr;
  PngError error;

  PngHandle() {
    png = kWriting
              ? png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, onPngError, onPngWarning)
              : png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, onPngError, onPngWarning);
    if (png != nullptr) {
      info = png_create_info_struct(png);
    }
  }
  ~PngHandle() {
    if constexpr (kWriting) {
      png_destroy_write_struct(&png, &info);
    } else {
      png_destroy_read_struct(&png, &info, nullptr);
    }
  }
  PngHandle(const PngHandle&) = delete;
  PngHandle& operator=(const PngHandle&) = delete;
};
using PngWriter = PngHandle<true>;
using PngReader = PngHandle<false>;

// ---- writing -------------------------------------------------------------------------------

/// Where encoded bytes go: a file, or the end of a vector.
struct PngSink {
  std::FILE* file = nullptr;
  std::vector<std::uint8_t>* memory = nullptr;
  int compression_level = -1;  ///< zlib's 0 to 9; -1 libpng's default
};

void appendToMemory(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(png));
  try {
    out->insert(out->end(), data, data + length);
  } catch (const std::bad_alloc&) {
    png_error(png, "out of memory");  // no exception may cross libpng's C frames
  }
}

void flushNothing(png_structp) {}

/// False when libpng reported an error (its message is in the writer's PngError).
bool encode(PngWriter& writer, const PngSink& sink, const Image& image, png_bytepp rows) {
  if (setjmp(png_jmpbuf(writer.png)) != 0) {
    return false;
  }
  if (sink.memory != nullptr) {
    png_set_write_fn(writer.png, sink.memory, appendToMemory, flushNothing);
  } else {
    png_init_io(writer.png, sink.file);
  }
  if (sink.compression_level >= 0) {
    png_set_compression_level(writer.png, sink.compression_level);
  }
  png_set_IHDR(writer.png, writer.info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(writer.png, writer.info);
  png_write_image(writer.png, rows);
  png_write_end(writer.png, nullptr);
  return true;
}

// ---- reading -------------------------------------------------------------------------------

/// Reads the header and asks libpng to deliver 8-bit RGB whatever the file holds. False on error.
/// Bytes in memory being read.
struct PngSource {
  const std::uint8_t* data;
  std::size_t size;
  std::size_t at = 0;
};

void readFromMemory(png_structp png, png_bytep data, png_size_t length) {
  auto* source = static_cast<PngSource*>(png_get_io_ptr(png));
  if (length > source->size - source->at) {
    png_error(png, "the PNG ends early");
  }
  std::memcpy(data, source->data + source->at, length);
  source->at += length;
}

/// `file`, or when null `memory`.
bool readHeader(PngReader& reader, std::FILE* file, PngSource* memory, png_uint_32* width,
                png_uint_32* height) {
  if (setjmp(png_jmpbuf(reader.png)) != 0) {
    return false;
  }
  if (file != nullptr) {
    png_init_io(reader.png, file);
  } else {
    png_set_read_fn(reader.png, memory, readFromMemory);
  }
  png_read_info(reader.png, reader.info);
  png_set_expand(reader.png);  // palette -> RGB, gray < 8 bit -> 8 bit, tRNS -> alpha
  png_set_strip_16(reader.png);
  png_set_strip_alpha(reader.png);
  png_set_gray_to_rgb(reader.png);
  png_set_interlace_handling(reader.png);
  png_read_update_info(reader.png, reader.info);
  *width = png_get_image_width(reader.png, reader.info);
  *height = png_get_image_height(reader.png, reader.info);
  if (png_get_rowbytes(reader.png, reader.info) != static_cast<std::size_t>(*width) * 3) {
    png_error(reader.png, "unexpected row layout after conversion to 8-bit RGB");
  }
  return true;
}

bool readRows(PngReader& reader, png_bytepp rows) {
  if (setjmp(png_jmpbuf(reader.png)) != 0) {
    return false;
  }
  png_read_image(reader.png, rows);
  png_read_end(reader.png, nullptr);
  return true;
}

std::vector<png_bytep> rowPointers(std::uint8_t* rgb, int width, int height) {
  std::vector<png_bytep> rows(static_cast<std::size_t>(height));
  for (std::size_t y = 0; y < rows.size(); ++y) {
    rows[y] = rgb + y * byteCount(width, 1);
  }
  return rows;
}

}  // namespace

void writePng(const Image& image, const std::filesystem::path& file) {
  checkLayout(image, "writePng");
  if (image.empty()) {
    throw SimError("writePng: cannot write an empty image to " + quoted(file));
  }
  const FileHandle handle = openFile(file, "wb", "writePng");
  PngWriter writer;
  if (writer.info == nullptr) {
    throw SimError("writePng: libpng could not allocate its state for " + quoted(file));
  }
  // libpng's row pointers are non-const although writing only reads through them.
  auto* pixels = const_cast<std::uint8_t*>(image.rgb.data());
  std::vector<png_bytep> rows = rowPointers(pixels, image.width, image.height);
  if (!encode(writer, PngSink{.file = handle.get()}, image, rows.data())) {
    throw SimError("writePng: cannot write " + quoted(file) + ": " + writer.error.message);
  }
  // Buffered bytes reach the disk only here, so a full disk shows up now rather than in encode.
  if (std::fflush(handle.get()) != 0 || std::ferror(handle.get()) != 0) {
    throw SimError("writePng: cannot write " + quoted(file) + ": " + std::strerror(errno));
  }
}

namespace {

/// Reads from `file`, or when null from `memory`; errors name `what`.
Image readPngFrom(std::FILE* file, PngSource* memory, const std::string& what) {
  PngReader reader;
  if (reader.info == nullptr) {
    throw SimError("readPng: libpng could not allocate its state for " + what);
  }
  png_uint_32 width = 0;
  png_uint_32 height = 0;
  if (!readHeader(reader, file, memory, &width, &height)) {
    throw SimError("readPng: cannot read " + what + ": " + reader.error.message);
  }
  // libpng's default user limits keep both dimensions far below INT_MAX.
  Image image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  image.rgb.resize(byteCount(image.width, image.height));
  std::vector<png_bytep> rows = rowPointers(image.rgb.data(), image.width, image.height);
  if (!readRows(reader, rows.data())) {
    throw SimError("readPng: cannot read " + what + ": " + reader.error.message);
  }
  return image;
}

}  // namespace

Image readPng(const std::filesystem::path& file) {
  const FileHandle handle = openFile(file, "rb", "readPng");
  return readPngFrom(handle.get(), nullptr, quoted(file));
}

std::vector<std::uint8_t> encodePng(const Image& image, int compression_level) {
  checkLayout(image, "encodePng");
  if (image.empty()) {
    throw SimError("encodePng: cannot encode an empty image");
  }
  PngWriter writer;
  if (writer.info == nullptr) {
    throw SimError("encodePng: libpng could not allocate its state");
  }
  std::vector<std::uint8_t> bytes;
  bytes.reserve(image.rgb.size() / 2 + 1024);
  auto* pixels = const_cast<std::uint8_t*>(image.rgb.data());
  std::vector<png_bytep> rows = rowPointers(pixels, image.width, image.height);
  const PngSink sink{.memory = &bytes, .compression_level = std::clamp(compression_level, 0, 9)};
  if (!encode(writer, sink, image, rows.data())) {
    throw SimError(std::string("encodePng: ") + writer.error.message);
  }
  return bytes;
}

Image decodePng(std::span<const std::uint8_t> bytes) {
  PngSource source{bytes.data(), bytes.size()};
  return readPngFrom(nullptr, &source, "a PNG of " + std::to_string(bytes.size()) + " bytes");
}

Image sideBySide(const std::vector<Image>& images, int gap_px,
                 std::array<std::uint8_t, 3> background) {
  const int gap = std::max(gap_px, 0);
  Image result;
  int placed = 0;
  for (const Image& image : images) {
    checkLayout(image, "sideBySide");
    if (!image.empty()) {
      result.width += (placed++ > 0 ? gap : 0) + image.width;
      result.height = std::max(result.height, image.height);
    }
  }
  if (result.empty()) {
    return Image{};
  }
  result.rgb.resize(byteCount(result.width, result.height));
  for (std::size_t i = 0; i < result.rgb.size(); i += 3) {
    std::copy(background.begin(), background.end(), result.rgb.begin() + static_cast<long>(i));
  }
  const std::size_t row_bytes = byteCount(result.width, 1);
  std::size_t left_bytes = 0;
  for (const Image& image : images) {
    if (image.empty()) {
      continue;
    }
    const std::size_t image_row_bytes = byteCount(image.width, 1);
    for (std::size_t y = 0; y < static_cast<std::size_t>(image.height); ++y) {
      std::memcpy(result.rgb.data() + y * row_bytes + left_bytes,
                  image.rgb.data() + y * image_row_bytes, image_row_bytes);
    }
    left_bytes += image_row_bytes + byteCount(gap, 1);
  }
  return result;
}

double fractionDifferentFrom(const Image& image, std::array<std::uint8_t, 3> background,
                             int tolerance) {
  checkLayout(image, "fractionDifferentFrom");
  if (image.empty()) {
    return 0.0;
  }
  std::size_t different = 0;
  for (std::size_t i = 0; i < image.rgb.size(); i += 3) {
    for (std::size_t c = 0; c < 3; ++c) {
      if (std::abs(int{image.rgb[i + c]} - int{background[c]}) > tolerance) {
        ++different;
        break;
      }
    }
  }
  return static_cast<double>(different) / static_cast<double>(image.rgb.size() / 3);
}

}  // namespace comply::sim
