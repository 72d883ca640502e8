#pragma once
// A fork and join for the planner's parallel loops (bar candidates, groups
// of points): the work is the caller's, the threads are not kept.
#include <functional>

namespace scaffold::plan {

// Runs work(0) on the calling thread and work(1) .. work(n - 1) on threads
// of their own, and returns when all have; then rethrows what the lowest
// numbered worker that failed threw.
void run_workers(int n, const std::function<void(int)>& work);

}  // namespace scaffold::plan
