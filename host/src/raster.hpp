// scatterlut — an 8-bit RGB raster with filled rectangles and text in a 5×7 bitmap font,
// enough to draw a labelled false-colour picture (inspect --preview) without a graphics
// library.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace scatterlut {

struct Rgb {
    uint8_t r, g, b;
};

struct Raster {
    int width = 0, height = 0;
    std::vector<uint8_t> rgb; // row-major from the top row, 3 bytes per pixel

    Raster(int w, int h, Rgb background);
    void set(int x, int y, Rgb c);                 // ignores pixels outside the raster
    Rgb get(int x, int y) const;
    void fill(int x, int y, int w, int h, Rgb c);  // clipped to the raster
    // Text with its top-left corner at (x, y), each font pixel drawn as scale × scale.
    // Printable ASCII; any other byte is drawn as '?'.
    void text(int x, int y, const std::string &s, Rgb c, int scale);
};

// The font's cell: 5 × 7 glyphs above the baseline (descenders 2 rows below), advanced by
// 6 columns; lines 10 rows apart (unscaled).
inline constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphAdvance = 6, kLineAdvance = 10;
inline int text_width(const std::string &s, int scale) {
    return s.empty() ? 0 : (static_cast<int>(s.size()) * kGlyphAdvance - 1) * scale;
}

} // namespace scatterlut
