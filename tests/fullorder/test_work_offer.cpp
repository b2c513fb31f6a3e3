// WorkOffer (fullorder/work_offer.hpp): an offer runs on the serving thread and to completion, or
// — nobody serving — not at all; an exception of the offering thread's own part is rethrown only
// after an offer under way has finished; close() ends the serving.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "fullorder/work_offer.hpp"

namespace mastrom::fullorder {
namespace {

/// Wait (bounded) until the serving thread has said it serves.
void waitUntilServing(const WorkOffer& offer) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!offer.secondThreadFree() && std::chrono::steady_clock::now() < give_up)
    std::this_thread::yield();
  ASSERT_TRUE(offer.secondThreadFree());
}

TEST(WorkOffer, AnOfferRunsOnTheServingThreadToCompletion) {
  WorkOffer offer;
  offer.open();
  std::thread server([&] { offer.serve(); });
  waitUntilServing(offer);
  const std::thread::id here = std::this_thread::get_id();
  int taken = 0;
  for (int round = 0; round < 20; ++round) {
    std::thread::id ran_on;
    std::atomic<bool> finished{false};
    const bool ran = offer.run(
        [&] {
          // The own part lasts long enough for a serving thread to take the offer.
          const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(20);
          while (std::chrono::steady_clock::now() < until) std::this_thread::yield();
        },
        [&] {
          ran_on = std::this_thread::get_id();
          std::this_thread::sleep_for(std::chrono::milliseconds(1));
          finished = true;
        });
    if (ran) {
      ++taken;
      EXPECT_NE(ran_on, here);
      EXPECT_TRUE(finished.load());  // run() returned only after the offer had finished
    } else {
      EXPECT_FALSE(finished.load());
    }
  }
  offer.close();
  server.join();
  EXPECT_GE(taken, 1);  // each round may go either way on a loaded machine, not all of them
  EXPECT_FALSE(offer.secondThreadFree());
}

TEST(WorkOffer, WithNobodyServingTheOfferIsWithdrawnUnrun) {
  WorkOffer offer;
  offer.open();
  EXPECT_FALSE(offer.secondThreadFree());
  bool first_ran = false, second_ran = false;
  EXPECT_FALSE(offer.run([&] { first_ran = true; }, [&] { second_ran = true; }));
  EXPECT_TRUE(first_ran);
  EXPECT_FALSE(second_ran);
  // A server that starts afterwards finds nothing to run and stops at close().
  std::thread server([&] { offer.serve(); });
  waitUntilServing(offer);
  offer.close();
  server.join();
  EXPECT_FALSE(second_ran);
}

TEST(WorkOffer, AnExceptionOfTheOwnPartWaitsForTheOfferUnderWay) {
  WorkOffer offer;
  offer.open();
  std::thread server([&] { offer.serve(); });
  waitUntilServing(offer);
  std::atomic<bool> started{false}, finished{false};
  EXPECT_THROW(offer.run(
                   [&] {
                     const auto give_up =
                         std::chrono::steady_clock::now() + std::chrono::seconds(10);
                     while (!started.load() && std::chrono::steady_clock::now() < give_up)
                       std::this_thread::yield();  // until the server has taken it
                     throw std::runtime_error("own part failed");
                   },
                   [&] {
                     started = true;
                     std::this_thread::sleep_for(std::chrono::milliseconds(20));
                     finished = true;
                   }),
               std::runtime_error);
  EXPECT_TRUE(finished.load());
  offer.close();
  server.join();
}

}  // namespace
}  // namespace mastrom::fullorder
