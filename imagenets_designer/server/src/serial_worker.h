// One thread that runs queued jobs in order: the Designer's requests, one at a time, away from
// the network thread (a run may take seconds; cancel must still get through).
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>

namespace imagenets {
namespace designer {

class SerialWorker {
 public:
  SerialWorker();
  ~SerialWorker();  // runs the jobs already queued, then stops
  void post(std::function<void()> job);

 private:
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> jobs_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace designer
}  // namespace imagenets
