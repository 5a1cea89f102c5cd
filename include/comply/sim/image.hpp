#pragma once
// An RGB image in memory and its PNG file form: what snapshots and side-by-side figures are made
// of.

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace comply::sim {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  ///< width * height * 3 bytes, rows top to bottom

  [[nodiscard]] bool empty() const noexcept { return width == 0 || height == 0; }
};

/// Writes `image` as an 8-bit RGB PNG. Throws SimError naming the file on any failure.
void writePng(const Image& image, const std::filesystem::path& file);
/// Reads a PNG as 8-bit RGB: RGB and RGBA as they are (alpha dropped, not composited); gray,
/// palette and 16-bit images are converted. Throws SimError naming the file.
Image readPng(const std::filesystem::path& file);
/// `image` as the bytes of a PNG file, compressed at zlib's `compression_level` (0 to 9; 1 is
/// the fast level a recording takes per frame). Throws SimError for an empty or malformed image.
std::vector<std::uint8_t> encodePng(const Image& image, int compression_level = 1);
/// A PNG file's bytes as 8-bit RGB, as readPng converts them. Throws SimError on bad bytes.
Image decodePng(std::span<const std::uint8_t> bytes);

/// The images left to right, top-aligned, `gap_px` columns of `background` between them; shorter
/// images are padded with `background` at the bottom.
Image sideBySide(const std::vector<Image>& images, int gap_px = 8,
                 std::array<std::uint8_t, 3> background = {255, 255, 255});

/// Fraction of pixels that differ from `background` by more than `tolerance` in any channel.
double fractionDifferentFrom(const Image& image, std::array<std::uint8_t, 3> background,
                             int tolerance = 8);

}  // namespace comply::sim
