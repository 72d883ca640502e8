#include "plan/workers.hpp"

#include <exception>
#include <thread>
#include <vector>

namespace scaffold::plan {

void run_workers(int n, const std::function<void(int)>& work) {
    std::vector<std::exception_ptr> failed(static_cast<std::size_t>(std::max(n, 1)));
    auto guarded = [&](int w) {
        try {
            work(w);
        } catch (...) {
            failed[static_cast<std::size_t>(w)] = std::current_exception();
        }
    };
    std::vector<std::thread> pool;
    for (int w = 1; w < n; ++w) pool.emplace_back(guarded, w);
    guarded(0);
    for (std::thread& t : pool) t.join();
    for (const std::exception_ptr& e : failed)
        if (e) std::rethrow_exception(e);
}

}  // namespace scaffold::plan
