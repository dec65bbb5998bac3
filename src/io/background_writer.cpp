// A trajectory writer whose samples are formatted and written on a thread of their own while the run
// steps on. Turning a sample of 10⁵ bodies into CSV text takes about as long as 60 rk4 steps of them
// (4.5·10⁶ shortest round-trip numbers at ~45 ns), so a run that samples often spends a fifth of its
// time there; beside the stepping it is free on a second core.
//
// One sample is in flight at a time: write() waits until the thread has finished the previous one,
// copies the state into the one slot (its vectors keep their capacity: no allocation after the first
// sample) and returns. Every other call waits until the thread is idle and then calls the inner writer
// itself, so the inner writer is never entered by two threads at once and sees its calls in the order
// the run made them: the files are the same bytes as without the thread. An error on the thread is
// thrown by every later call from the run (commit() at the latest), so nothing is written after it.
#include <condition_variable>
#include <csignal>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>

#include <pthread.h>

#include "tumble/io/trajectory_writer.hpp"

namespace tumble {
namespace {

class BackgroundWriter final : public TrajectoryWriter {
 public:
  /// Takes `inner` once its thread has started; if none can be started (std::system_error: a limit on
  /// threads or on memory), `inner` is left with the caller.
  explicit BackgroundWriter(std::unique_ptr<TrajectoryWriter>& inner) : inner_(std::move(inner)) {
    try {
      thread_ = std::thread([this] { work(); });
    } catch (const std::system_error&) {
      inner = std::move(inner_);
      throw;
    }
  }

  ~BackgroundWriter() override {
    {
      std::unique_lock lock(mutex_);
      idle_.wait(lock, [this] { return !pending_; });
      stop_ = true;
    }
    wake_.notify_one();
    thread_.join();
  }

  void write(const Model& model, const SystemState& state, const DriftSample& drift) override {
    wait_idle();
    model_ = &model;
    slot_ = state;
    drift_ = drift;
    {
      const std::lock_guard lock(mutex_);
      pending_ = true;
    }
    wake_.notify_one();
  }
  void event(std::string_view name, size_t row, double t) override {
    wait_idle();
    inner_->event(name, row, t);
  }
  void outcome(double wall_time_s, const std::vector<std::string>& warnings) override {
    wait_idle();
    inner_->outcome(wall_time_s, warnings);
  }
  void commit(bool complete) override {
    wait_idle();
    inner_->commit(complete);
  }
  std::vector<std::filesystem::path> outputs() const override { return inner_->outputs(); }
  long samples() const override {
    std::unique_lock lock(mutex_);
    idle_.wait(lock, [this] { return !pending_; });
    return inner_->samples();
  }
  void sync() override {
    wait_idle();
    inner_->sync();
  }

 private:
  /// Waits until the thread has written the sample in flight; throws what writing it threw.
  void wait_idle() {
    std::unique_lock lock(mutex_);
    idle_.wait(lock, [this] { return !pending_; });
    if (error_) std::rethrow_exception(error_);
  }

  void work() {
    // The run's signals (Ctrl-C, SIGTERM, a batch system's SIGXCPU) are for the thread that can stop
    // the run and write its checkpoint, not for this one.
    sigset_t run_signals;
    sigemptyset(&run_signals);
    for (const int s : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGXCPU, SIGUSR1, SIGUSR2, SIGALRM}) {
      sigaddset(&run_signals, s);
    }
    pthread_sigmask(SIG_BLOCK, &run_signals, nullptr);
    std::unique_lock lock(mutex_);
    for (;;) {
      wake_.wait(lock, [this] { return pending_ || stop_; });
      if (stop_) return;
      lock.unlock();
      std::exception_ptr error;
      try {
        inner_->write(*model_, slot_, drift_);
      } catch (...) {
        error = std::current_exception();
      }
      lock.lock();
      error_ = error;
      pending_ = false;
      idle_.notify_all();
    }
  }

  std::unique_ptr<TrajectoryWriter> inner_;
  const Model* model_ = nullptr;  // of the sample in flight
  SystemState slot_;
  DriftSample drift_;
  mutable std::mutex mutex_;
  mutable std::condition_variable idle_;
  std::condition_variable wake_;
  bool pending_ = false, stop_ = false;
  std::exception_ptr error_;
  std::thread thread_;  // started in the constructor's body, once everything it reads exists
};

}  // namespace

std::unique_ptr<TrajectoryWriter> write_in_background(std::unique_ptr<TrajectoryWriter> inner) {
  try {
    return std::make_unique<BackgroundWriter>(inner);
  } catch (const std::system_error&) {
    return inner;  // no thread to be had: written on the caller's thread, the same bytes, a little later
  }
}

}  // namespace tumble
