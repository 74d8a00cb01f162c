// The background writer of output files (io/background_writer.hpp): every job runs, at most
// kMaxInFlight at once, and a job's error reaches the caller while the other jobs still finish.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

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

TEST_CASE("background writer: a job's error is rethrown and the other jobs still finish", "[io][writer]") {
  std::atomic<int> done{0};
  BackgroundWriter writer;
  writer.submit([] { throw std::runtime_error("disk full"); });
  writer.submit([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ++done;
  });
  CHECK_THROWS_WITH(writer.finish(), "disk full");
  CHECK(done == 1);
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
