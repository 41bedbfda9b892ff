// The LCM types against the planner's enums, and the guarded decoder against the
// payloads that abort LCM 1.3.1's typed subscription.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "base/solve_status.h"
#include "lcmtypes/message_guard.h"
#include "mfp/plan_request_t.hpp"
#include "mfp/plan_t.hpp"
#include "mfp/status_t.hpp"
#include "mfp/terrain_map_t.hpp"

namespace mfp {
namespace {

template <class Message>
std::vector<uint8_t> Encode(const Message& m) {
  std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
  EXPECT_EQ(m.encode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
  return bytes;
}

plan_request_t MakeRequest(int legs, const std::string& robot) {
  plan_request_t m;
  m.utime = 123;
  m.request_id = 42;
  m.robot = robot;
  m.num_legs = legs;
  for (int i = 0; i < legs; ++i) m.start_feet.push_back({0.1 * i, -0.2 * i, 0.01});
  m.goal_x = 1.0;
  m.goal_y = 2.0;
  m.goal_yaw = 0.5;
  m.max_steps = 12;
  m.time_limit_s = 3.0;
  return m;
}

terrain_map_t MakeMap(size_t bytes) {
  terrain_map_t m;
  m.utime = 7;
  m.frame = "world";
  m.format = "bt";
  m.num_bytes = static_cast<int32_t>(bytes);
  for (size_t i = 0; i < bytes; ++i) m.data.push_back(static_cast<uint8_t>(i * 31));
  return m;
}

void WriteInt32(std::vector<uint8_t>* bytes, size_t at, int32_t v) {
  const auto u = static_cast<uint32_t>(v);
  for (int i = 0; i < 4; ++i) (*bytes)[at + static_cast<size_t>(i)] = static_cast<uint8_t>(u >> (24 - 8 * i));
}

// Offset of plan_request_t.num_legs for a robot name of `name_length` characters.
size_t NumLegsOffset(size_t name_length) { return 8 + 8 + 8 + 4 + name_length + 1; }

TEST(LcmTypesTest, StatusConstantsMirrorSolveStatus) {
  EXPECT_EQ(+plan_t::STATUS_OPTIMAL, static_cast<int>(SolveStatus::kOptimal));
  EXPECT_EQ(+plan_t::STATUS_FEASIBLE, static_cast<int>(SolveStatus::kFeasible));
  EXPECT_EQ(+plan_t::STATUS_TIME_LIMIT, static_cast<int>(SolveStatus::kTimeLimit));
  EXPECT_EQ(+plan_t::STATUS_INFEASIBLE, static_cast<int>(SolveStatus::kInfeasible));
  EXPECT_EQ(+plan_t::STATUS_INVALID_REQUEST, static_cast<int>(SolveStatus::kInvalidRequest));
  EXPECT_EQ(+plan_t::STATUS_NO_MAP, static_cast<int>(SolveStatus::kNoMap));
  EXPECT_EQ(+plan_t::STATUS_INVALID_START, static_cast<int>(SolveStatus::kInvalidStart));
  EXPECT_EQ(+plan_t::STATUS_INVALID_GOAL, static_cast<int>(SolveStatus::kInvalidGoal));
  EXPECT_EQ(+plan_t::STATUS_INTERNAL_ERROR, static_cast<int>(SolveStatus::kInternalError));
  EXPECT_EQ(+plan_t::STATUS_NO_SOLUTION, static_cast<int>(SolveStatus::kNoSolution));
  EXPECT_EQ(+plan_t::STATUS_DROPPED, static_cast<int>(SolveStatus::kDropped));
  EXPECT_EQ(+plan_t::STATUS_SUPERSEDED, static_cast<int>(SolveStatus::kSuperseded));
  EXPECT_EQ(+plan_t::STATUS_PARTIAL, static_cast<int>(SolveStatus::kPartial));
  EXPECT_EQ(+plan_t::STATUS_NO_ROUTE, static_cast<int>(SolveStatus::kNoRoute));
  // Every SolveStatus has a constant: the last one is the highest value.
  EXPECT_EQ(ToString(static_cast<SolveStatus>(+plan_t::STATUS_NO_ROUTE)), "no_route");
}

TEST(LcmTypesTest, WireWalkersMatchTheGeneratedEncoders) {
  // A walker that disagrees with the schema (a field added to the .lcm file but not to
  // message_guard.cc) would reject these valid messages.
  for (int legs : {0, 1, 4, 6, kMaxWireLegs}) {
    for (const std::string& robot : {std::string(), std::string("hexapod"), std::string(300, 'r')}) {
      const auto bytes = Encode(MakeRequest(legs, robot));
      EXPECT_EQ(CheckWireLayout(static_cast<const plan_request_t*>(nullptr), bytes.data(), bytes.size()), "")
          << legs << " legs";
    }
  }
  for (size_t n : {0, 1, 1000}) {
    const auto bytes = Encode(MakeMap(n));
    EXPECT_EQ(CheckWireLayout(static_cast<const terrain_map_t*>(nullptr), bytes.data(), bytes.size()), "");
  }
}

TEST(LcmTypesTest, ValidMessagesDecode) {
  const plan_request_t sent = MakeRequest(6, "hexapod");
  const auto bytes = Encode(sent);
  plan_request_t got;
  ASSERT_EQ(DecodeGuarded(bytes.data(), bytes.size(), 1 << 16, &got), "");
  EXPECT_EQ(got.request_id, 42);
  EXPECT_EQ(got.robot, "hexapod");
  ASSERT_EQ(got.start_feet.size(), 6u);
  EXPECT_DOUBLE_EQ(got.start_feet[5][1], -1.0);

  const auto map_bytes = Encode(MakeMap(500));
  terrain_map_t map;
  ASSERT_EQ(DecodeGuarded(map_bytes.data(), map_bytes.size(), 1 << 20, &map), "");
  EXPECT_EQ(map.data.size(), 500u);
}

TEST(LcmTypesTest, RejectsTruncatedAndTrailingBytes) {
  const auto bytes = Encode(MakeRequest(4, "littledog"));
  for (size_t n = 0; n < bytes.size(); ++n) {
    plan_request_t got;
    EXPECT_NE(DecodeGuarded(bytes.data(), n, 1 << 16, &got), "") << n << " bytes";
  }
  auto longer = bytes;
  longer.push_back(0);
  plan_request_t got;
  EXPECT_NE(DecodeGuarded(longer.data(), longer.size(), 1 << 16, &got), "");
}

TEST(LcmTypesTest, RejectsWrongFingerprint) {
  auto bytes = Encode(MakeRequest(4, ""));
  bytes[3] ^= 0x40;
  plan_request_t got;
  EXPECT_NE(DecodeGuarded(bytes.data(), bytes.size(), 1 << 16, &got).find("fingerprint"),
            std::string::npos);
  // A valid message of another type on the request channel.
  const auto map_bytes = Encode(MakeMap(10));
  EXPECT_NE(DecodeGuarded(map_bytes.data(), map_bytes.size(), 1 << 16, &got), "");
}

TEST(LcmTypesTest, RejectsNegativeAndHugeLengths) {
  const std::string robot = "hexapod";
  for (int32_t legs : {-1, -6, INT32_MIN, kMaxWireLegs + 1, 100000000, INT32_MAX}) {
    auto bytes = Encode(MakeRequest(6, robot));
    WriteInt32(&bytes, NumLegsOffset(robot.size()), legs);
    plan_request_t got;
    const std::string why = DecodeGuarded(bytes.data(), bytes.size(), 1 << 16, &got);
    EXPECT_NE(why.find("num_legs"), std::string::npos) << legs << ": " << why;
  }
  // The robot string's length: negative, zero (no room for the NUL) and past the end.
  for (int32_t len : {-1, 0, 1000, INT32_MAX}) {
    auto bytes = Encode(MakeRequest(6, robot));
    WriteInt32(&bytes, 24, len);
    plan_request_t got;
    EXPECT_NE(DecodeGuarded(bytes.data(), bytes.size(), 1 << 16, &got), "") << len;
  }
  // terrain_map_t.num_bytes after "world" and "bt".
  const size_t num_bytes_at = 8 + 8 + (4 + 6) + (4 + 3);
  for (int32_t n : {-1, INT32_MIN, 11, INT32_MAX}) {
    auto bytes = Encode(MakeMap(10));
    WriteInt32(&bytes, num_bytes_at, n);
    terrain_map_t got;
    EXPECT_NE(DecodeGuarded(bytes.data(), bytes.size(), 1 << 16, &got), "") << n;
  }
}

TEST(LcmTypesTest, RejectsOversizedPayloads) {
  const auto bytes = Encode(MakeMap(5000));
  terrain_map_t got;
  const std::string why = DecodeGuarded(bytes.data(), bytes.size(), 4096, &got);
  EXPECT_NE(why.find("above the limit"), std::string::npos) << why;
}

TEST(LcmTypesTest, RandomPayloadsNeverCrash) {
  std::mt19937 rng(5);
  const auto valid = Encode(MakeRequest(6, "hexapod"));
  for (int trial = 0; trial < 20000; ++trial) {
    std::vector<uint8_t> bytes;
    if (trial % 2 == 0) {
      bytes.resize(rng() % 300);
      for (auto& b : bytes) b = static_cast<uint8_t>(rng());
    } else {
      // Valid fingerprint, a few bytes flipped: exercises the walker past the hash.
      bytes = valid;
      for (int k = 0; k < 3; ++k) bytes[8 + rng() % (bytes.size() - 8)] = static_cast<uint8_t>(rng());
    }
    plan_request_t got;
    const std::string why = DecodeGuarded(bytes.data(), bytes.size(), 1 << 16, &got);
    if (why.empty()) {
      EXPECT_LE(got.start_feet.size(), static_cast<size_t>(kMaxWireLegs));
    }
  }
}

}  // namespace
}  // namespace mfp
