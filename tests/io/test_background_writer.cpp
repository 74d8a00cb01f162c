// The background writer of output files (io/background_writer.hpp): every job runs, one at a
// time in the order submitted (a checkpoint never lands before the fields it vouches for), and a
// job's error reaches the caller while the jobs after it do not run.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "roller/io/background_writer.hpp"

using namespace roller;

TEST_CASE("background writer: every job runs, never more than the bound at once", "[io][writer]") {
  std::atomic<int> done{0}, running{0}, most{0};
  {
    BackgroundWriter writer;
    for (int i = 0; i < 8; ++i)
      writer.submit([&] {
        const int now = ++running;
        int seen = most.load();
        while (now > seen && !most.compare_exchange_weak(seen, now)) {
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        --running;
        ++done;
      });
    writer.finish();
    CHECK(done == 8);
  }
  CHECK(most.load() <= BackgroundWriter::kMaxInFlight);
  CHECK(most.load() >= 1);
}

TEST_CASE("background writer: jobs run one at a time in the order submitted", "[io][writer]") {
  // The first job is slow: a writer that ran the second beside it (the checkpoint beside the
  // step's VTU) would record the second first.
  std::mutex m;
  std::vector<int> order;
  std::atomic<int> running{0}, most{0};
  BackgroundWriter writer;
  for (int i = 0; i < 6; ++i)
    writer.submit([&, i] {
      most = std::max(most.load(), ++running);
      std::this_thread::sleep_for(std::chrono::milliseconds(i % 2 == 0 ? 30 : 1));
      {
        const std::lock_guard<std::mutex> lock(m);
        order.push_back(i);
      }
      --running;
    });
  writer.finish();
  CHECK(order == std::vector<int>{0, 1, 2, 3, 4, 5});
  CHECK(most.load() == 1);
}

TEST_CASE("background writer: a job's error is rethrown and the jobs after it do not run", "[io][writer]") {
  // A VTU that could not be written must not be followed by the checkpoint that vouches for it.
  std::atomic<int> done{0};
  BackgroundWriter writer;
  writer.submit([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    throw std::runtime_error("disk full");
  });
  writer.submit([&] { ++done; });
  CHECK_THROWS_WITH(writer.finish(), "disk full");
  CHECK(done == 0);
  CHECK_NOTHROW(writer.finish());  // collected once
}

TEST_CASE("background writer in the foreground runs each job inside submit", "[io][writer]") {
  BackgroundWriter writer(false);
  const auto caller = std::this_thread::get_id();
  std::thread::id ran_on;
  writer.submit([&] { ran_on = std::this_thread::get_id(); });
  CHECK(ran_on == caller);
  CHECK_THROWS_WITH(writer.submit([] { throw std::runtime_error("disk full"); }), "disk full");
}

TEST_CASE("background writer: what the jobs captured is released once they ran (memory stays bounded)",
          "[io][writer]") {
  // Each job captures a payload (a step's fields in a run); a writer that kept finished jobs'
  // captures alive (a chain of predecessors) would hold all 20 by the end.
  static std::atomic<int> live{0};
  struct Payload {
    Payload() { ++live; }
    Payload(const Payload&) { ++live; }
    ~Payload() { --live; }
  };
  int most = 0;
  {
    BackgroundWriter writer;
    for (int i = 0; i < 20; ++i) {
      writer.submit([p = std::make_shared<Payload>()] { std::this_thread::sleep_for(std::chrono::milliseconds(2)); });
      most = std::max(most, live.load());
    }
    writer.finish();
  }
  CHECK(most <= BackgroundWriter::kMaxInFlight + 1);
  CHECK(live.load() == 0);
}
