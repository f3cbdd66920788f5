#include "gpu/workgroup_order.h"

#include <vector>

namespace vkray::gpu {

void spreadForContiguousSplits(std::span<std::uint32_t> items) {
    const std::size_t count = items.size();
    int bits = 0;
    while ((std::size_t(1) << bits) < count) ++bits;
    const std::vector<std::uint32_t> original(items.begin(), items.end());
    std::size_t next = 0;
    for (std::size_t j = 0; j < (std::size_t(1) << bits); ++j) {
        std::size_t reversed = 0;
        for (int b = 0; b < bits; ++b) reversed |= ((j >> b) & 1u) << (bits - 1 - b);
        if (reversed < count) items[next++] = original[reversed];
    }
}

}  // namespace vkray::gpu
