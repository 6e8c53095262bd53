// The queue between the thread that makes the servo ticks and the one that measures and writes them
// (planning/tick_queue.hpp): every tick arrives once, in order, whatever the batch size and however the two
// threads' speeds differ; the producer's error arrives after its last tick; a consumer that gives up stops
// the producer instead of leaving it blocked.
#include "planning/tick_queue.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <random>
#include <thread>

namespace pkm::planning {
namespace {

ServoTick numbered(long k) {
  ServoTick tick;
  tick.index = k;
  tick.s = 0.5 * static_cast<double>(k);
  tick.line = static_cast<int>(k % 97);
  return tick;
}

TEST(TickQueue, EveryTickArrivesOnceInOrderThenTheProducersError) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    const std::size_t batch = 1 + rng() % 40, batches = 1 + rng() % 5;
    const long ticks = static_cast<long>(rng() % 3000);
    const bool fails = trial % 3 == 0;
    // Now one side is slower, now the other: a pause every so many ticks.
    const long producer_pause = 1 + static_cast<long>(rng() % 500), consumer_pause = 1 + rng() % 500;
    TickQueue queue(batch, batches);
    std::thread producer([&] {
      for (long k = 0; k < ticks; ++k) {
        ASSERT_TRUE(queue.push(numbered(k)));
        if (k % producer_pause == 0) std::this_thread::sleep_for(std::chrono::microseconds(50));
      }
      queue.close(fails ? std::optional<Error>(Error{ErrorCode::unreachable, "out of reach"}) : std::nullopt);
    });
    ServoTick tick;
    long received = 0;
    while (queue.pop(tick)) {
      ASSERT_EQ(tick.index, received) << "trial " << trial;
      ASSERT_EQ(tick.s, 0.5 * static_cast<double>(received));
      if (received % static_cast<long>(consumer_pause) == 0)
        std::this_thread::sleep_for(std::chrono::microseconds(50));
      ++received;
    }
    producer.join();
    EXPECT_EQ(received, ticks) << "batches of " << batch << " × " << batches;
    EXPECT_EQ(queue.error().has_value(), fails);
    EXPECT_FALSE(queue.pop(tick)) << "the end stays the end";
  }
}

TEST(TickQueue, AConsumerThatGivesUpStopsTheProducer) {
  TickQueue queue(16, 2);
  long pushed = 0;
  std::thread producer([&] {
    while (queue.push(numbered(pushed))) ++pushed;  // would never end without the cancel
    queue.close(std::nullopt);
  });
  ServoTick tick;
  for (int k = 0; k < 100; ++k) ASSERT_TRUE(queue.pop(tick));
  queue.cancel();
  producer.join();
  // At most the ring's worth beyond what was read.
  EXPECT_LE(pushed, 100 + 3 * 16);
}

}  // namespace
}  // namespace pkm::planning
