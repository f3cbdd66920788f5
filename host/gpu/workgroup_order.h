// The order in which a dispatch lists its workgroups. llvmpipe (Mesa 22.3's
// lp_cs_tpool) splits a dispatch's workgroups into one contiguous run for
// each of its threads, decided before any runs: with the tile's groups in
// rows, the thread given the half of a tile that shows most of a scene works
// while the other waits. Listed in bit-reversed order, every contiguous run
// of the list is an even sample of the tile, whatever the number of threads.
#pragma once

#include <cstdint>
#include <span>

namespace vkray::gpu {

// Reorders `items` so that position j holds the item at the bit-reversal of
// j (over the fewest bits that count them all), the positions whose
// reversal lies past the end left out: items 0, 2, 4, ... come first, then
// 1, 3, 5, ...; each half, quarter or eighth of the result takes one item
// in every two, four or eight of the original, spread over all of it.
void spreadForContiguousSplits(std::span<std::uint32_t> items);

}  // namespace vkray::gpu
