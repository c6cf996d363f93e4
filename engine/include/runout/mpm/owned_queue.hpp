#pragma once
// Work handed out owner first (the CPU backend's scatters and cell groups,
// backend_openmp.hpp): each thread takes the items of its own list, then
// those left in the others' lists, so that the load stays balanced.
#include <atomic>
#include <vector>

namespace runout {

class OwnedQueue {
 public:
  void reset(int lists) {
    if (static_cast<int>(lists_.size()) != lists) {
      lists_.resize(lists);
      taken_ = std::vector<std::atomic<int>>(lists);
    }
    for (int l = 0; l < lists; ++l) {
      lists_[l].clear();
      taken_[l].store(0, std::memory_order_relaxed);
    }
  }
  void add(int list, int item) { lists_[list].push_back(item); }
  // f(item) for each item this thread takes; on every thread, each item once.
  template <class F>
  void run(int thread, F&& f) {
    const int lists = static_cast<int>(lists_.size());
    for (int u = 0; u < lists; ++u) {
      const int l = (thread + u) % lists;
      const int size = static_cast<int>(lists_[l].size());
      for (int at; (at = taken_[l].fetch_add(1, std::memory_order_relaxed)) < size;)
        f(lists_[l][at]);
    }
  }

 private:
  std::vector<std::vector<int>> lists_;
  std::vector<std::atomic<int>> taken_;  // how far each list has been handed out
};

}  // namespace runout
