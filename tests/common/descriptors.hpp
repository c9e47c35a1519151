#pragma once
// Closes every descriptor a forked test child inherited, except stdin, stdout, stderr and `keep`.
// A child that tests the server out of descriptors sets a low limit; whatever the test runner
// left open (CI harnesses leave dozens) would otherwise use that budget up before the test begins.
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <vector>

namespace arena::test {

inline void close_inherited_descriptors(std::vector<int> keep = {}) {
    std::sort(keep.begin(), keep.end());
    unsigned first = 3;
    for (int fd : keep) {
        if (fd < 3) continue;
        if (static_cast<unsigned>(fd) > first) ::close_range(first, static_cast<unsigned>(fd) - 1, 0);
        first = std::max(first, static_cast<unsigned>(fd) + 1);
    }
    ::close_range(first, UINT_MAX, 0);
}

}  // namespace arena::test
