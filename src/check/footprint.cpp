#include "check/footprint.hpp"

namespace scaffold::check {

bool Footprint::covers(int gi, int gj) {
    const int i = gi - i0, j = gj - j0, nx = grid.width(), ny = grid.height();
    if (i < 0 || j < 0 || i >= nx || j >= ny) return false;
    if (grid.get(i, j)) return true;
    const std::size_t at = static_cast<std::size_t>(j) * nx + i;
    if (state[at]) return state[at] == 1;
    queue_.clear();
    queue_.push_back(static_cast<int>(at));
    state[at] = 3;  // visiting
    bool open = false;
    for (std::size_t q = 0; q < queue_.size() && !open; ++q) {
        const int c = queue_[q], ci = c % nx, cj = c / nx;
        if (ci == 0 || cj == 0 || ci == nx - 1 || cj == ny - 1 || queue_.size() > limit) {
            open = true;
            break;
        }
        const int next[4][2] = {{ci - 1, cj}, {ci + 1, cj}, {ci, cj - 1}, {ci, cj + 1}};
        for (const auto& n : next) {
            const std::size_t k = static_cast<std::size_t>(n[1]) * nx + n[0];
            if (grid.get(n[0], n[1])) continue;
            // A cell an earlier flood found open: this region is that one
            // (that flood stopped at the limit before reaching here), not a
            // hole walled in by its cells.
            if (state[k] == 2) {
                open = true;
                break;
            }
            if (state[k]) continue;
            state[k] = 3;
            queue_.push_back(static_cast<int>(k));
        }
    }
    // An open flood stopped early: the cells it reached belong to the same
    // large region; the rest are found open on their own.
    for (int c : queue_) state[static_cast<std::size_t>(c)] = open ? 2 : 1;
    return !open;
}

}  // namespace scaffold::check
