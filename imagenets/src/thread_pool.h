// A fixed pool of worker threads. A thread that waits for work it posted helps run queued tasks
// instead of sleeping, so nested waits (a feedback sweep inside a run, a sub-net inside a block)
// can never starve the pool; with 0 workers the waiting thread runs everything itself.
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace imagenets {

class ThreadPool {
 public:
  explicit ThreadPool(int workers);
  ~ThreadPool();

  int size() const { return static_cast<int>(workers_.size()); }
  void post(std::function<void()> task);
  // Runs queued tasks on this thread until done() holds. done() is called with the pool locked;
  // whoever makes it true must call notify() afterwards.
  void helpUntil(const std::function<bool()>& done);
  void notify();

 private:
  void work();
  // Runs the oldest queued task with the pool unlocked, then wakes every waiter: the task may have
  // finished what a helper waits for. `lock` holds mutex_; a task is queued.
  void runOldest(std::unique_lock<std::mutex>& lock);

  std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<std::function<void()>> tasks_;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace imagenets
