// Which tiles of a frame a renderer traces, and who hears when each is done.
// One process traces every tile of tilesOf, row by row, two in flight;
// `vkray render` under mpirun hands tiles out across the ranks instead
// (host/dist/distributed_render.*), one at a time.
#pragma once

#include <algorithm>
#include <cstddef>
#include <optional>
#include <vector>

namespace vkray {

struct Frame;

// A rectangle of pixels; x and y are multiples of the render's block.
struct TileRect {
    int x = 0, y = 0, width = 0, height = 0;
};

// The tiles of a width x height image, `side` pixels square (the last row and
// column smaller), top to bottom, left to right; `serpentine`: every other
// row right to left, so that consecutive tiles are neighbours (a benchmark
// experiment, BENCHMARKS.md).
inline std::vector<TileRect> tilesOf(int width, int height, int side, bool serpentine = false) {
    std::vector<TileRect> tiles;
    for (int y = 0, row = 0; y < height; y += side, ++row) {
        const std::size_t rowStart = tiles.size();
        for (int x = 0; x < width; x += side)
            tiles.push_back(
                {x, y, side < width - x ? side : width - x, side < height - y ? side : height - y});
        if (serpentine && row % 2 == 1) std::reverse(tiles.begin() + long(rowStart), tiles.end());
    }
    return tiles;
}

class TileSchedule {
public:
    virtual ~TileSchedule() = default;
    // Before the first tile: the image and the tile side this renderer would
    // pick (a multiple of the block that fits the device's limits). A tile
    // that next() returns may be larger; the renderer splits it.
    virtual void plan(int width, int height, int tileSide) = 0;
    // The next tile to trace, or none when the frame is done.
    virtual std::optional<TileRect> next() = 0;
    // `tile` of `frame` is traced.
    virtual void finished(const TileRect& tile, const Frame& frame) = 0;
};

}  // namespace vkray
