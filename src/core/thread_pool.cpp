#include "core/thread_pool.h"

#include <omp.h>
#include <pthread.h>

#include <algorithm>
#include <atomic>
#include <ctime>
#include <exception>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace periflex {
namespace {

// One turn of a waiting thread's spin: tells the core that this is a wait, which frees its pipeline
// for a sibling hyper-thread and saves power.
inline void spin_pause() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

// Set on a team's worker threads, and on a caller while its loop runs: a parallel_for called there
// runs inline (the team is busy with the loop that called it).
thread_local bool t_in_loop = false;

// The innermost TeamSizeScope's count on this thread; 0: none
thread_local int t_team_size = 0;

// Items a loop hands out at once: the claim word holds the count in its low 32 bits.
constexpr int64_t kMaxItemsPerRound = int64_t{1} << 31;

class Team {
 public:
  // The process's one team. It is never destroyed: its workers are detached and wait for work
  // until the process ends, and a loop may still run on another thread while the process exits.
  static Team& instance() {
    static Team* team = new Team();
    return *team;
  }

  void run(int64_t count, void (*call)(void*, int64_t), void* context);
  double worker_cpu_seconds();

 private:
  // A worker's mailbox, on its own cache line: the number of the job it is asked to join, and
  // whether it sleeps (then the caller wakes it).
  struct alignas(64) Worker {
    std::atomic<uint32_t> ticket{0};
    std::atomic<uint32_t> sleeping{0};
  };

  void add_workers(int wanted);
  void work(Worker& me);
  void take_items(uint32_t job);

  std::mutex loop_lock_;  // held by the thread whose loop the team runs
  std::vector<std::unique_ptr<Worker>> workers_;
  std::mutex clocks_lock_;
  std::vector<clockid_t> clocks_;  // each worker's processor-time clock

  // The running job. Its description is written before claim_ is published and read by a worker
  // only after it took an item of that job, so it cannot change while that item runs.
  uint32_t job_ = 0;
  uint32_t count_ = 0;
  void (*call_)(void*, int64_t) = nullptr;
  void* context_ = nullptr;
  std::exception_ptr error_;
  std::atomic<bool> failed_{false};
  // (job << 32) | items not yet taken; an item is taken by lowering the count while the job
  // number still matches, so a worker that wakes after its job ended takes nothing.
  alignas(64) std::atomic<uint64_t> claim_{0};
  alignas(64) std::atomic<uint32_t> done_{0};  // items of the job finished
  std::atomic<uint32_t> caller_sleeping_{0};
};

void Team::add_workers(int wanted) {
  while (static_cast<int>(workers_.size()) < wanted) {
    workers_.push_back(std::make_unique<Worker>());
    Worker& worker = *workers_.back();
    std::thread thread([this, &worker] { work(worker); });
    clockid_t clock{};
    const bool has_clock = pthread_getcpuclockid(thread.native_handle(), &clock) == 0;
    thread.detach();
    if (has_clock) {
      std::lock_guard<std::mutex> lock(clocks_lock_);
      clocks_.push_back(clock);
    }
  }
}

void Team::take_items(uint32_t job) {
  uint64_t claim = claim_.load(std::memory_order_acquire);
  for (;;) {
    if (static_cast<uint32_t>(claim >> 32) != job || (claim & 0xffffffffu) == 0) return;
    if (!claim_.compare_exchange_weak(claim, claim - 1, std::memory_order_acq_rel, std::memory_order_acquire))
      continue;
    // the job cannot end before this item is counted as done: its description still holds
    const uint32_t count = count_;
    if (!failed_.load(std::memory_order_relaxed)) {
      try {
        call_(context_, static_cast<int64_t>(claim & 0xffffffffu) - 1);
      } catch (...) {
        if (!failed_.exchange(true)) error_ = std::current_exception();
      }
    }
    if (done_.fetch_add(1) + 1 == count && caller_sleeping_.load() != 0) done_.notify_one();
    claim = claim_.load(std::memory_order_acquire);
  }
}

void Team::work(Worker& me) {
  t_in_loop = true;
  uint32_t seen = 0;
  for (;;) {
    uint32_t job = me.ticket.load(std::memory_order_acquire);
    for (int turn = 0; job == seen && turn < kSpinTurns; ++turn) {
      spin_pause();
      job = me.ticket.load(std::memory_order_acquire);
    }
    if (job == seen) {
      // announced before the last look, so a caller that posts a job after that look sees it
      me.sleeping.store(1);
      while ((job = me.ticket.load()) == seen) me.ticket.wait(seen);
      me.sleeping.store(0);
    }
    seen = job;
    take_items(job);
  }
}

void Team::run(int64_t count, void (*call)(void*, int64_t), void* context) {
  const int team = static_cast<int>(std::min<int64_t>(team_size(), count));
  std::unique_lock<std::mutex> lock;
  if (team > 1 && !t_in_loop) lock = std::unique_lock<std::mutex>(loop_lock_, std::try_to_lock);
  if (!lock.owns_lock()) {
    for (int64_t item = 0; item < count; ++item) call(context, item);
    return;
  }
  // a worker the system refuses to start leaves its share to the others
  try {
    add_workers(team - 1);
  } catch (const std::system_error&) {
  }
  const int posted = std::min(team - 1, static_cast<int>(workers_.size()));
  t_in_loop = true;

  job_ = job_ + 1 == 0 ? 1 : job_ + 1;  // 0 is the number no job has: a new worker has seen it
  count_ = static_cast<uint32_t>(count);
  call_ = call;
  context_ = context;
  error_ = nullptr;
  failed_.store(false, std::memory_order_relaxed);
  done_.store(0, std::memory_order_relaxed);
  claim_.store((static_cast<uint64_t>(job_) << 32) | count_, std::memory_order_release);
  for (int w = 0; w < posted; ++w) {
    Worker& worker = *workers_[w];
    worker.ticket.store(job_);
    if (worker.sleeping.load() != 0) worker.ticket.notify_one();
  }

  take_items(job_);
  // the caller waits for the items, not for the workers: one that never woke took none
  uint32_t done = done_.load(std::memory_order_acquire);
  for (int turn = 0; done != count_ && turn < kSpinTurns; ++turn) {
    spin_pause();
    done = done_.load(std::memory_order_acquire);
  }
  if (done != count_) {
    caller_sleeping_.store(1);
    while ((done = done_.load()) != count_) done_.wait(done);
    caller_sleeping_.store(0);
  }
  t_in_loop = false;
  if (failed_.load()) std::rethrow_exception(error_);
}

double Team::worker_cpu_seconds() {
  std::lock_guard<std::mutex> lock(clocks_lock_);
  double total = 0.0;
  for (clockid_t clock : clocks_) {
    timespec ts{};
    if (clock_gettime(clock, &ts) == 0) total += static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  }
  return total;
}

}  // namespace

namespace detail {

void run_on_team(int64_t count, void (*call)(void*, int64_t), void* context) {
  if (count <= kMaxItemsPerRound) {
    Team::instance().run(count, call, context);
    return;
  }
  // larger loops in rounds whose counts fit the claim word
  for (int64_t first = 0; first < count; first += kMaxItemsPerRound) {
    const int64_t round = std::min(count - first, kMaxItemsPerRound);
    struct Offset {
      void (*call)(void*, int64_t);
      void* context;
      int64_t first;
    } offset{call, context, first};
    Team::instance().run(
        round,
        [](void* shifted, int64_t item) {
          const auto* o = static_cast<Offset*>(shifted);
          o->call(o->context, o->first + item);
        },
        &offset);
  }
}

}  // namespace detail

double team_worker_cpu_seconds() { return Team::instance().worker_cpu_seconds(); }

int team_size() { return t_team_size > 0 ? t_team_size : omp_get_max_threads(); }

TeamSizeScope::TeamSizeScope(int threads) : previous_(t_team_size) {
  if (threads > 0) t_team_size = threads;
}

TeamSizeScope::~TeamSizeScope() { t_team_size = previous_; }

}  // namespace periflex
