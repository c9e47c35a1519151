#pragma once
// The threads that tick the matches (--threads): run(count, job) calls job(0..count-1) on
// the pool's threads and the calling one, an item to whichever is free next, and returns when
// every call has returned. Between runs the threads sleep. A job must not throw.
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace arena::host {

class tick_pool {
public:
    // `threads` in all, the caller's included: 1 starts none.
    explicit tick_pool(unsigned threads);
    ~tick_pool();
    tick_pool(const tick_pool&) = delete;
    tick_pool& operator=(const tick_pool&) = delete;

    unsigned threads() const { return static_cast<unsigned>(workers_.size()) + 1; }
    void run(size_t count, const std::function<void(size_t)>& job);

private:
    void work();
    void take_items();

    std::vector<std::thread> workers_;
    std::mutex mutex_;
    std::condition_variable start_;
    std::condition_variable done_;
    uint64_t generation_ = 0;  // one more per run: what a sleeping thread waits for
    const std::function<void(size_t)>* job_ = nullptr;
    size_t count_ = 0;
    std::atomic<size_t> next_{0};
    size_t busy_ = 0;  // pool threads not yet done with the current run
    bool stopping_ = false;
};

}  // namespace arena::host
