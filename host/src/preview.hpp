// scatterlut — a false-colour picture of a table (`scatterlut inspect FILE --preview
// out.png`): one channel over two axes (a 2-D table, or a 2-D slice of a 3-D/4-D one)
// or over one axis (a 1-D table), with the axes labelled in parameter units (ticks placed
// through the axis warp), the table nodes marked on the edges, a colour bar with the
// value scale, and a caption saying which slice is shown.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "raster.hpp"
#include "scatterlut/table.hpp"

namespace scatterlut {

struct PreviewRequest {
    std::string title;                  // first caption line, e.g. the file name
    std::string channel;                // channel name; "" = channel 0
    std::vector<std::string> plot_axes; // {x} or {x, y} by name; empty = axis 0 (and axis 1)
    // The other axes, "NAME=VALUE,NAME=#NODE,…": VALUE in the axis's parameter units
    // (within [min, max], interpolated like the sampler), #NODE a node index. Axes not
    // named sit at their middle node, (count − 1)/2.
    std::string slice;
};

struct SliceAxis {
    size_t axis;
    double param; // parameter value of the slice
    int node;     // its node index, or -1 between nodes
};

struct PreviewTick {
    double pos;        // 0 … 1 along the axis: unit coordinate, or fraction of the colour bar
    std::string label; // in parameter units (axes) or quantity units (colour bar)
};

struct Preview {
    Raster image{1, 1, {0, 0, 0}};
    // Plot area in image pixels: column i shows unit coordinate (i + 0.5)/plot_w of the
    // x axis, row j (from the top) unit coordinate 1 − (j + 0.5)/plot_h of the y axis.
    int plot_x = 0, plot_y = 0, plot_w = 0, plot_h = 0;
    size_t channel = 0;
    size_t x_axis = 0;
    int y_axis = -1;                    // -1: a single plotted axis
    std::vector<SliceAxis> slice;       // every axis not plotted
    double value_lo = 0, value_hi = 0;  // stored (encoded) values at the colour bar's ends
    std::string slice_text;             // the caption's slice line
    std::vector<PreviewTick> x_ticks, y_ticks, bar_ticks;
};

// Throws std::invalid_argument for a request the table cannot satisfy (unknown channel or
// axis, an axis both plotted and sliced, a slice value outside the axis, …).
Preview render_preview(const Table &table, const PreviewRequest &request);

// Viridis (van der Walt & Smith, matplotlib; CC0): t ∈ [0, 1] → sRGB, lightness increasing
// monotonically from dark blue-violet to yellow. t is clamped.
Rgb viridis(double t);

} // namespace scatterlut
