// The daemon core in-process: replies for bad requests, the bounded newest-first queue,
// counters for unreadable messages, and the live runner over memq:// (bad payloads,
// heartbeat during a slow plan). A fake planner and a fake map reader keep it fast;
// daemon_replay_test runs the real ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <random>
#include <system_error>
#include <thread>

#include "base/check.h"
#include "daemon/daemon_config.h"
#include "daemon/daemon_core.h"
#include "daemon/daemon_runner.h"
#include "daemon/daemon_setup.h"
#include "lcmtypes/lcm_transport.h"
#include "lcmtypes/message_guard.h"
#include "mfp/region_set_t.hpp"
#include "mfp/terrain_map_t.hpp"
#include "test_temp_path.h"

namespace mfp {
namespace {

struct Recorded {
  std::string channel;
  std::vector<uint8_t> bytes;
};

class RecordingPublisher final : public Publisher {
 public:
  bool Publish(const std::string& channel, const void* data, size_t size) override {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto* p = static_cast<const uint8_t*>(data);
    messages_.push_back({channel, std::vector<uint8_t>(p, p + size)});
    return true;
  }
  template <class Message>
  std::vector<Message> All(const std::string& channel) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<Message> out;
    for (const Recorded& r : messages_) {
      if (r.channel != channel) continue;
      Message m;
      EXPECT_EQ(DecodeGuarded(r.bytes.data(), r.bytes.size(), 1 << 24, &m), "");
      out.push_back(m);
    }
    return out;
  }

 private:
  std::mutex mutex_;
  std::vector<Recorded> messages_;
};

// Test maps: "flat" is one 4 m square at z = 0 (no seen surface); anything else is unreadable.
MapTerrain FakeMap(const std::string& bytes, const std::string& /*format*/, const std::string& what) {
  if (bytes != "flat") throw InputError(what + ": not a test map");
  return {{MakeRegionFromPolygon(0, {{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}}, 0.01)}, nullptr, nullptr, ""};
}

// Plans nothing: returns the start stance as an optimal plan.
Plan FakePlan(const RobotModel& robot, const std::vector<ConvexRegion>& /*regions*/,
              const PlanRequest& request, const PlannerOptions& /*options*/) {
  Plan plan;
  plan.status = SolveStatus::kOptimal;
  plan.reaches_goal = true;
  plan.solve_time_s = 0.001;
  for (int i = 0; i < robot.num_legs(); ++i) {
    Footstep f;
    f.index = i;
    f.leg = robot.gait[static_cast<size_t>(i)];
    f.position_world_m = request.start_feet_world_m[static_cast<size_t>(f.leg)];
    f.region_id = 0;
    plan.footsteps.push_back(f);
  }
  return plan;
}

// Robots are derived from their URDFs once for the whole test program.
const DaemonSetup& BaseSetup() {
  static const DaemonSetup setup = [] {
    DaemonConfig config;
    config.file = "test";
    config.robot_files = {std::string(MFP_SOURCE_DIR) + "/config/robots/hexapod.yaml",
                          std::string(MFP_SOURCE_DIR) + "/config/robots/littledog.yaml"};
    config.default_robot = "hexapod";
    config.limits.max_request_bytes = 4096;
    config.limits.max_map_bytes = 1 << 20;
    return LoadDaemonSetup(config);
  }();
  return setup;
}

std::shared_ptr<const DaemonSetup> TestSetup(int queue_size, bool supersede = true) {
  auto setup = std::make_shared<DaemonSetup>(BaseSetup());
  setup->config.limits.queue_size = queue_size;
  setup->config.limits.supersede_same_robot = supersede;
  return setup;
}

// Nominal stance of a robot on flat ground at the origin, in leg order.
plan_request_t Request(const RobotModel& robot, int64_t id) {
  plan_request_t m{};  // no robot name (the default robot), goal y and yaw 0
  m.utime = 1;
  m.request_id = id;
  m.num_legs = robot.num_legs();
  for (const LegModel& leg : robot.legs)
    m.start_feet.push_back({leg.nominal_offset_body_m.x(), leg.nominal_offset_body_m.y(), 0.0});
  m.goal_x = 0.5;
  m.max_steps = 12;
  m.time_limit_s = 1.0;
  return m;
}

template <class Message>
std::vector<uint8_t> Encode(const Message& m) {
  std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

terrain_map_t MapMessage(const std::string& content) {
  terrain_map_t m;
  m.utime = 99;
  m.frame = "world";
  m.format = "bt";
  m.data.assign(content.begin(), content.end());
  m.num_bytes = static_cast<int32_t>(m.data.size());
  return m;
}

RawMessage Raw(const std::string& channel, const std::vector<uint8_t>& bytes) {
  RawMessage raw;
  raw.channel = channel;
  raw.data = bytes.data();
  raw.size = bytes.size();
  return raw;
}

// The malformed payloads of the issue, for the request channel.
std::vector<std::vector<uint8_t>> BadPayloads(const RobotModel& robot) {
  std::vector<std::vector<uint8_t>> bad;
  const auto valid = Encode(Request(robot, 500));
  bad.emplace_back(valid.begin(), valid.begin() + static_cast<long>(valid.size() / 2));  // truncated
  std::mt19937 rng(1);
  std::vector<uint8_t> random(200);
  for (auto& b : random) b = static_cast<uint8_t>(rng());
  bad.push_back(random);  // random
  auto fingerprint = valid;
  fingerprint[0] ^= 0xff;
  bad.push_back(fingerprint);  // wrong fingerprint
  plan_request_t negative = Request(robot, 501);
  negative.num_legs = -1;  // the encoder writes the length and no elements
  negative.start_feet.clear();
  bad.push_back(Encode(negative));
  bad.emplace_back(8192, 0);  // oversized
  bad.emplace_back();         // empty
  return bad;
}

double SecondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

class DaemonCoreTest : public ::testing::Test {
 protected:
  void Make(int queue_size, PlanFunction plan = FakePlan, bool supersede = true) {
    setup_ = TestSetup(queue_size, supersede);
    core_ = std::make_unique<DaemonCore>(setup_, FakeMap, std::move(plan), publisher_,
                                         [this] { return ++now_; });
  }
  void Send(const plan_request_t& m) {
    const auto bytes = Encode(m);
    core_->OnMessage(Raw(kPlanRequestChannel, bytes));
  }
  void SendMap(const std::string& content) {
    const auto bytes = Encode(MapMessage(content));
    core_->OnMessage(Raw(kTerrainMapChannel, bytes));
  }
  const RobotModel& Hexapod() const { return setup_->robots.at("hexapod"); }
  std::vector<plan_t> Replies() { return publisher_.All<plan_t>(kPlanChannel); }
  // The replies so far are requests 1 and 2, in that order, each with `status` and a
  // message that says `words`.
  void ExpectRequestsOneAndTwoAnswered(int8_t status, const std::string& words) {
    const std::vector<plan_t> replies = Replies();
    ASSERT_EQ(replies.size(), 2u);
    EXPECT_EQ(replies[0].request_id, 1);
    EXPECT_EQ(replies[1].request_id, 2);
    for (const plan_t& r : replies) {
      EXPECT_EQ(r.status, status);
      EXPECT_NE(r.message.find(words), std::string::npos) << r.message;
    }
  }

  // One hexapod request with a 0.2 s limit to a daemon whose planner is `plan`: the reply
  // must come within 1 s (the overrunning planners take 3 s). Returns the replies.
  // Sends the request, plans it and returns its reply, the only one so far (an empty
  // plan_t when there is none, a failure).
  plan_t PlanTheOnlyRequest(const plan_request_t& request) {
    Send(request);
    EXPECT_TRUE(core_->PlanNext());
    const std::vector<plan_t> replies = Replies();
    EXPECT_EQ(replies.size(), 1u);
    return replies.empty() ? plan_t{} : replies.front();
  }

  // A 0.2 s request to a planner that overruns it: its reply, sent within 1 s.
  plan_t PlanPastTheDeadline(PlanFunction plan) {
    Make(4, std::move(plan));
    SendMap("flat");
    plan_request_t request = Request(Hexapod(), 1);
    request.time_limit_s = 0.2;
    const auto start = std::chrono::steady_clock::now();
    const plan_t reply = PlanTheOnlyRequest(request);
    EXPECT_LT(SecondsSince(start), 1.0);
    return reply;
  }

  RecordingPublisher publisher_;
  std::shared_ptr<const DaemonSetup> setup_;
  std::unique_ptr<DaemonCore> core_;
  int64_t now_ = 0;
};

TEST_F(DaemonCoreTest, RequestBeforeAnyMapIsAnsweredNoMap) {
  Make(4);
  Send(Request(Hexapod(), 7));
  const auto replies = Replies();
  ASSERT_EQ(replies.size(), 1u);
  EXPECT_EQ(replies[0].request_id, 7);
  EXPECT_EQ(replies[0].status, +plan_t::STATUS_NO_MAP);
  EXPECT_NE(replies[0].message.find("no terrain map"), std::string::npos);
  EXPECT_FALSE(core_->PlanNext());
}

TEST_F(DaemonCoreTest, MapPublishesRegionsAndRequestIsPlanned) {
  Make(4);
  SendMap("flat");
  const auto sets = publisher_.All<region_set_t>(kRegionsChannel);
  ASSERT_EQ(sets.size(), 1u);
  EXPECT_EQ(sets[0].num_regions, 1);
  EXPECT_EQ(sets[0].map_utime, 99);
  const plan_t reply = PlanTheOnlyRequest(Request(Hexapod(), 8));
  EXPECT_EQ(reply.request_id, 8);
  EXPECT_EQ(reply.status, +plan_t::STATUS_OPTIMAL);
  EXPECT_EQ(reply.num_steps, 6);
  EXPECT_EQ(reply.robot, "hexapod");
  EXPECT_EQ(reply.map_utime, 99);
}

TEST_F(DaemonCoreTest, BadRequestsGetAStatusThatNamesTheProblem) {
  Make(4);
  SendMap("flat");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    std::function<void(plan_request_t*)> change;
    int8_t status;
    std::string names;
  };
  const std::vector<Case> cases = {
      {[&](plan_request_t* m) { m->goal_x = nan; }, plan_t::STATUS_INVALID_REQUEST, "goal_x = nan"},
      {[&](plan_request_t* m) { m->start_feet[2][0] = inf; }, plan_t::STATUS_INVALID_REQUEST,
       "start_feet[2][0] = inf"},
      {[&](plan_request_t* m) { m->time_limit_s = -inf; }, plan_t::STATUS_INVALID_REQUEST,
       "time_limit_s = -inf"},
      {[&](plan_request_t* m) {
         m->num_legs = 4;
         m->start_feet.resize(4);
       },
       plan_t::STATUS_INVALID_REQUEST, "num_legs = 4 but robot 'hexapod' has 6 legs"},
      {[&](plan_request_t* m) { m->robot = "spot"; }, plan_t::STATUS_INVALID_REQUEST,
       "unknown robot 'spot'"},
      {[&](plan_request_t* m) { m->max_steps = 100000; }, plan_t::STATUS_INVALID_REQUEST,
       "max_steps = 100000"},
      {[&](plan_request_t* m) { m->max_steps = -1; }, plan_t::STATUS_INVALID_REQUEST,
       "max_steps = -1"},
      {[&](plan_request_t* m) { m->time_limit_s = 1000; }, plan_t::STATUS_INVALID_REQUEST,
       "time_limit_s = 1000"},
      {[&](plan_request_t* m) { m->start_feet[3] = {5.0, 0.0, 0.0}; }, plan_t::STATUS_INVALID_START,
       "leg 3 ('hind')"},
      {[&](plan_request_t* m) { m->start_feet[1][2] = 0.3; }, plan_t::STATUS_INVALID_START,
       "leg 1 ('front_left')"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    plan_request_t m = Request(Hexapod(), static_cast<int64_t>(100 + i));
    cases[i].change(&m);
    Send(m);
  }
  const auto replies = Replies();
  ASSERT_EQ(replies.size(), cases.size());
  for (size_t i = 0; i < cases.size(); ++i) {
    EXPECT_EQ(replies[i].request_id, static_cast<int64_t>(100 + i));
    EXPECT_EQ(replies[i].status, cases[i].status) << replies[i].message;
    EXPECT_NE(replies[i].message.find(cases[i].names), std::string::npos)
        << "'" << replies[i].message << "' does not name '" << cases[i].names << "'";
  }
  EXPECT_FALSE(core_->PlanNext());
  EXPECT_EQ(core_->counters().invalid_requests, static_cast<int64_t>(cases.size()));
  EXPECT_EQ(core_->counters().requests, static_cast<int64_t>(cases.size()));
}

TEST_F(DaemonCoreTest, OtherRobotByName) {
  Make(4);
  SendMap("flat");
  plan_request_t m = Request(setup_->robots.at("littledog"), 9);
  m.robot = "littledog";
  const plan_t reply = PlanTheOnlyRequest(m);
  EXPECT_EQ(reply.status, +plan_t::STATUS_OPTIMAL) << reply.message;
  EXPECT_EQ(reply.num_steps, 4);
}

TEST_F(DaemonCoreTest, FullQueueDropsTheOldestWithAReplyAndServesNewestFirst) {
  Make(2, FakePlan, /*supersede=*/false);
  SendMap("flat");
  for (int64_t id = 1; id <= 4; ++id) Send(Request(Hexapod(), id));
  // Requests 1 and 2 were evicted by 3 and 4.
  ExpectRequestsOneAndTwoAnswered(plan_t::STATUS_DROPPED, "queue");
  EXPECT_EQ(core_->queue_length(), 2u);
  EXPECT_TRUE(core_->PlanNext());
  EXPECT_TRUE(core_->PlanNext());
  EXPECT_FALSE(core_->PlanNext());
  const std::vector<plan_t> replies = Replies();
  ASSERT_EQ(replies.size(), 4u);
  EXPECT_EQ(replies[2].request_id, 4);  // newest first
  EXPECT_EQ(replies[3].request_id, 3);
  EXPECT_EQ(core_->counters().dropped_requests, 2);
  EXPECT_EQ(core_->counters().plans, 4);
}

TEST_F(DaemonCoreTest, StopAnswersQueuedRequests) {
  Make(4, FakePlan, /*supersede=*/false);
  SendMap("flat");
  Send(Request(Hexapod(), 1));
  Send(Request(Hexapod(), 2));
  core_->Stop();
  const auto replies = Replies();
  ASSERT_EQ(replies.size(), 2u);
  for (const plan_t& r : replies) EXPECT_EQ(r.status, +plan_t::STATUS_DROPPED);
  EXPECT_FALSE(core_->PlanNext());
}

TEST_F(DaemonCoreTest, UnreadableMessagesAreCountedAndTheDaemonGoesOn) {
  Make(4);
  SendMap("flat");
  const auto bad = BadPayloads(Hexapod());
  for (const auto& payload : bad) core_->OnMessage(Raw(kPlanRequestChannel, payload));
  for (const auto& payload : bad) core_->OnMessage(Raw(kTerrainMapChannel, payload));
  SendMap("not a map");  // decodes, but the map reader rejects it
  const plan_t reply = PlanTheOnlyRequest(Request(Hexapod(), 77));
  EXPECT_EQ(reply.request_id, 77);
  EXPECT_EQ(reply.status, +plan_t::STATUS_OPTIMAL);
  const DaemonCounters c = core_->counters();
  EXPECT_EQ(c.rejected_messages, static_cast<int64_t>(2 * bad.size()));
  EXPECT_EQ(c.rejected_maps, 1);
  EXPECT_EQ(c.maps, 1);  // the good map is kept
  const status_t s = core_->StatusMessage();
  EXPECT_EQ(s.rejected_messages, c.rejected_messages);
  EXPECT_EQ(s.num_regions, 1);
  EXPECT_EQ(s.state, +status_t::STATE_IDLE);
}

TEST_F(DaemonCoreTest, PlannerFailureIsAnInternalErrorReply) {
  Make(4, [](const RobotModel&, const std::vector<ConvexRegion>&, const PlanRequest&,
             const PlannerOptions&) -> Plan { throw std::runtime_error("solver exploded"); });
  SendMap("flat");
  const plan_t reply = PlanTheOnlyRequest(Request(Hexapod(), 5));
  EXPECT_EQ(reply.status, +plan_t::STATUS_INTERNAL_ERROR);
  EXPECT_NE(reply.message.find("solver exploded"), std::string::npos);
}

TEST_F(DaemonCoreTest, ANewerRequestForTheSameRobotSupersedesTheQueuedOne) {
  Make(4);
  SendMap("flat");
  Send(Request(Hexapod(), 1));
  Send(Request(Hexapod(), 2));
  plan_request_t dog = Request(setup_->robots.at("littledog"), 3);
  dog.robot = "littledog";
  Send(dog);  // another robot: supersedes nothing
  Send(Request(Hexapod(), 4));
  ExpectRequestsOneAndTwoAnswered(plan_t::STATUS_SUPERSEDED, "superseded by request");
  EXPECT_EQ(core_->queue_length(), 2u);
  EXPECT_EQ(core_->counters().superseded_requests, 2);
  EXPECT_EQ(core_->StatusMessage().superseded_requests, 2);
}

TEST_F(DaemonCoreTest, TheDeadlineCountsFromArrival) {
  std::atomic<double> planner_limit{-1};
  Make(4, [&](const RobotModel& robot, const std::vector<ConvexRegion>& regions,
              const PlanRequest& request, const PlannerOptions& options) {
    planner_limit = request.time_limit_s;
    return FakePlan(robot, regions, request, options);
  });
  SendMap("flat");
  Send(Request(Hexapod(), 1));  // time limit 1 s
  now_ += 400000;               // 0.4 s in the queue
  ASSERT_TRUE(core_->PlanNext());
  EXPECT_GT(planner_limit.load(), 0.5);
  EXPECT_LE(planner_limit.load(), 0.6);  // what was left, less the reply margin
  Send(Request(Hexapod(), 2));
  now_ += 1100000;  // past its deadline before it is planned
  ASSERT_TRUE(core_->PlanNext());
  const auto replies = Replies();
  ASSERT_EQ(replies.size(), 2u);
  EXPECT_EQ(replies[1].status, +plan_t::STATUS_TIME_LIMIT);
  EXPECT_NE(replies[1].message.find("deadline passed in the queue"), std::string::npos);
  EXPECT_EQ(core_->counters().expired_requests, 1);
  EXPECT_EQ(core_->counters().time_limit_endings, 1);
}

// A planner that overruns its limit (it owns everything it touches: it is abandoned).
Plan SleepyPlan(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                const PlanRequest& request, const PlannerOptions& options) {
  std::this_thread::sleep_for(std::chrono::seconds(3));
  return FakePlan(robot, regions, request, options);
}

TEST_F(DaemonCoreTest, AnOverrunningPlannerIsAnsweredAtTheDeadline) {
  const plan_t reply = PlanPastTheDeadline(SleepyPlan);
  EXPECT_EQ(reply.status, +plan_t::STATUS_TIME_LIMIT);
  EXPECT_EQ(core_->counters().abandoned_solves, 1);
}

// Accepts one window (the start stance and one gait cycle, moved 5 cm), then overruns.
Plan OneWindowThenSleepyPlan(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                             const PlanRequest& request, const PlannerOptions& options) {
  Plan so_far = FakePlan(robot, regions, request, options);
  const int n = robot.num_legs();
  for (int i = 0; i < n; ++i) {
    Footstep f = so_far.footsteps[static_cast<size_t>(i)];
    f.index = n + i;
    f.position_world_m.x() += 0.05;
    so_far.footsteps.push_back(f);
  }
  so_far.status = SolveStatus::kPartial;
  so_far.reaches_goal = false;
  so_far.message = "the plan so far: 6 steps";
  request.on_plan_so_far(so_far);
  return SleepyPlan(robot, regions, request, options);
}

TEST_F(DaemonCoreTest, AtTheDeadlineTheReplyCarriesThePlanSoFar) {
  const plan_t reply = PlanPastTheDeadline(OneWindowThenSleepyPlan);
  EXPECT_EQ(reply.status, +plan_t::STATUS_PARTIAL);
  ASSERT_EQ(reply.num_steps, 2 * Hexapod().num_legs());
  EXPECT_NEAR(reply.steps[6].position[0],
              Hexapod().legs[static_cast<size_t>(reply.steps[6].leg)].nominal_offset_body_m.x() + 0.05, 1e-9);
  EXPECT_NE(reply.message.find("had not finished by the deadline"), std::string::npos) << reply.message;
  EXPECT_EQ(core_->counters().time_limit_endings, 1);
  EXPECT_EQ(core_->counters().abandoned_solves, 1);
}

TEST_F(DaemonCoreTest, ARobotsNextRequestStartsFromThePlanLastSentToIt) {
  std::mutex mutex;
  std::vector<size_t> warm_sizes;
  std::vector<std::vector<Footstep>> last_warm;
  Make(4, [&](const RobotModel& robot, const std::vector<ConvexRegion>& regions, const PlanRequest& request,
              const PlannerOptions& options) {
    std::lock_guard<std::mutex> lock(mutex);
    warm_sizes.push_back(request.warm_start.size());
    last_warm = request.warm_start;
    Plan plan = FakePlan(robot, regions, request, options);
    plan.footsteps[0].position_world_m.z() = 0.001 * static_cast<double>(warm_sizes.size());  // tells plans apart
    return plan;
  });
  SendMap("flat");
  Send(Request(Hexapod(), 1));
  ASSERT_TRUE(core_->PlanNext());
  plan_request_t dog = Request(setup_->robots.at("littledog"), 2);
  dog.robot = "littledog";
  Send(dog);
  ASSERT_TRUE(core_->PlanNext());
  Send(Request(Hexapod(), 3));
  ASSERT_TRUE(core_->PlanNext());
  {
    std::lock_guard<std::mutex> lock(mutex);
    ASSERT_EQ(warm_sizes.size(), 3u);
    EXPECT_EQ(warm_sizes[0], 0u);  // nothing sent to the hexapod yet
    EXPECT_EQ(warm_sizes[1], 0u);  // nor to the little dog: plans are per robot
    ASSERT_EQ(warm_sizes[2], 1u);  // the hexapod's first plan
    ASSERT_EQ(last_warm[0].size(), 6u);
    EXPECT_DOUBLE_EQ(last_warm[0][0].position_world_m.z(), 0.001);
  }
  Send(Request(Hexapod(), 5));
  ASSERT_TRUE(core_->PlanNext());
  {
    std::lock_guard<std::mutex> lock(mutex);
    ASSERT_EQ(warm_sizes.back(), 2u);  // its last plans, newest first
    EXPECT_DOUBLE_EQ(last_warm[0][0].position_world_m.z(), 0.003);
    EXPECT_DOUBLE_EQ(last_warm[1][0].position_world_m.z(), 0.001);
  }
  SendMap("flat");  // a new map: the old plans stood on the old one
  Send(Request(Hexapod(), 4));
  ASSERT_TRUE(core_->PlanNext());
  std::lock_guard<std::mutex> lock(mutex);
  EXPECT_EQ(warm_sizes.back(), 0u);
}

TEST_F(DaemonCoreTest, StopDuringAPlanAnswersItAndEveryQueuedRequest) {
  Make(4, SleepyPlan);
  SendMap("flat");
  Send(Request(Hexapod(), 1));
  std::thread worker([&] { core_->PlanNext(); });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  plan_request_t dog = Request(setup_->robots.at("littledog"), 2);
  dog.robot = "littledog";
  Send(dog);
  const auto start = std::chrono::steady_clock::now();
  core_->Stop();
  worker.join();
  EXPECT_LT(SecondsSince(start), 0.5);
  const auto replies = Replies();
  ASSERT_EQ(replies.size(), 2u);
  for (const plan_t& r : replies) EXPECT_EQ(r.status, +plan_t::STATUS_DROPPED) << r.message;
}

// A planner that ignores its time limit and ends only some time after its stop flag is
// set (a solver between checks), counting how many of it run at once.
struct StubbornPlanner {
  std::atomic<int> running{0};
  std::atomic<int> most{0};
  std::chrono::milliseconds wind_down{300};
  Plan operator()(const RobotModel& robot, const std::vector<ConvexRegion>& regions, const PlanRequest& request,
                  const PlannerOptions& options) {
    const int now = ++running;
    for (int seen = most.load(); now > seen && !most.compare_exchange_weak(seen, now);) {
    }
    while (!request.deadline.Stopped()) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    std::this_thread::sleep_for(wind_down);
    --running;
    return FakePlan(robot, regions, request, options);
  }
};

TEST_F(DaemonCoreTest, AbandonedPlansAreBoundedAndEveryRequestIsAnsweredOnce) {
  auto planner = std::make_shared<StubbornPlanner>();  // outlives the abandoned plans
  Make(4, [planner](const RobotModel& robot, const std::vector<ConvexRegion>& regions, const PlanRequest& request,
                    const PlannerOptions& options) { return (*planner)(robot, regions, request, options); });
  SendMap("flat");
  constexpr int kRequests = 30;
  for (int id = 1; id <= kRequests; ++id) {
    plan_request_t request = Request(Hexapod(), id);
    request.time_limit_s = 0.05;
    Send(request);
    ASSERT_TRUE(core_->PlanNext());
    EXPECT_LE(core_->counters().abandoned_plans_running, setup_->config.limits.max_abandoned_plans);
  }
  EXPECT_LE(planner->most.load(), setup_->config.limits.max_abandoned_plans);
  std::map<int64_t, int> answers;
  int dropped = 0;
  for (const plan_t& r : Replies()) {
    ++answers[r.request_id];
    if (r.status == plan_t::STATUS_DROPPED) {
      ++dropped;
      EXPECT_NE(r.message.find("limits.max_abandoned_plans"), std::string::npos) << r.message;
    } else {
      EXPECT_EQ(r.status, +plan_t::STATUS_TIME_LIMIT) << r.message;
    }
  }
  EXPECT_EQ(answers.size(), static_cast<size_t>(kRequests));
  for (const auto& [id, count] : answers) EXPECT_EQ(count, 1) << id;
  EXPECT_GT(dropped, 0);
  // Each abandoned plan had its stop flag set: all end within their wind-down.
  for (int i = 0; i < 100 && planner->running.load() > 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_EQ(planner->running.load(), 0);
  EXPECT_EQ(core_->counters().abandoned_plans_running, 0);
}

TEST_F(DaemonCoreTest, NoThreadForAPlanIsAnInternalErrorReplyNotACrash) {
  Make(4);
  SendMap("flat");
  core_->SetTaskLauncher([](std::function<void()>) {
    throw std::system_error(std::make_error_code(std::errc::resource_unavailable_try_again), "thread");
  });
  const plan_t reply = PlanTheOnlyRequest(Request(Hexapod(), 1));
  EXPECT_EQ(reply.status, +plan_t::STATUS_INTERNAL_ERROR);
  EXPECT_NE(reply.message.find("thread"), std::string::npos) << reply.message;
  EXPECT_EQ(core_->counters().internal_errors, 1);
  EXPECT_EQ(core_->counters().abandoned_plans_running, 0);
  core_->SetTaskLauncher(LaunchDetachedThread);  // threads again: planned
  Send(Request(Hexapod(), 2));
  ASSERT_TRUE(core_->PlanNext());
  EXPECT_EQ(Replies().back().status, +plan_t::STATUS_OPTIMAL);
}

TEST_F(DaemonCoreTest, AMapWithoutRegionsKeepsTheWorkingOneUnlessConfigured) {
  MapFunction maps = [](const std::string& bytes, const std::string& format,
                        const std::string& what) {
    return bytes == "empty" ? MapTerrain{} : FakeMap(bytes, format, what);
  };
  setup_ = TestSetup(4);
  core_ = std::make_unique<DaemonCore>(setup_, maps, FakePlan, publisher_, [this] { return ++now_; });
  SendMap("flat");
  SendMap("empty");
  EXPECT_EQ(core_->StatusMessage().num_regions, 1);
  EXPECT_EQ(core_->counters().empty_maps, 1);
  Send(Request(Hexapod(), 1));
  ASSERT_TRUE(core_->PlanNext());
  EXPECT_EQ(Replies().back().status, +plan_t::STATUS_OPTIMAL);

  auto accepting = std::make_shared<DaemonSetup>(*setup_);
  accepting->config.limits.accept_empty_maps = true;
  core_->Reconfigure(accepting);
  SendMap("empty");
  EXPECT_EQ(core_->StatusMessage().num_regions, 0);
}

class FailingPublisher final : public Publisher {
 public:
  bool Publish(const std::string&, const void*, size_t) override { return false; }
};

TEST_F(DaemonCoreTest, ANulInTheRobotNameIsAnsweredAndPublishFailuresAreCounted) {
  Make(4);
  SendMap("flat");
  plan_request_t request = Request(Hexapod(), 9);
  request.robot = "hexa?pod";
  // LCM's encoder stops at a NUL; a hand-made message carries one inside the string.
  auto bytes = Encode(request);
  const std::string marker = "hexa?pod";
  auto at = std::search(bytes.begin(), bytes.end(), marker.begin(), marker.end());
  ASSERT_NE(at, bytes.end());
  at[4] = 0;
  core_->OnMessage(Raw(kPlanRequestChannel, bytes));
  const auto replies = Replies();
  ASSERT_EQ(replies.size(), 1u);
  EXPECT_EQ(replies[0].status, +plan_t::STATUS_INVALID_REQUEST);
  EXPECT_NE(replies[0].message.find("hexa\\0pod"), std::string::npos) << replies[0].message;
  EXPECT_EQ(core_->counters().plans, 1);
  EXPECT_EQ(core_->counters().publish_failures, 0);

  FailingPublisher failing;
  DaemonCore core(setup_, FakeMap, FakePlan, failing, [this] { return ++now_; });
  bytes = Encode(Request(Hexapod(), 10));
  core.OnMessage(Raw(kPlanRequestChannel, bytes));  // no map: answered no_map, not sent
  EXPECT_EQ(core.counters().plans, 0);
  EXPECT_EQ(core.counters().publish_failures, 1);
  EXPECT_EQ(core.StatusMessage().publish_failures, 1);
}

int64_t SteadyUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

void Publish(LcmTransport& transport, const std::string& channel, const std::vector<uint8_t>& bytes) {
  ASSERT_TRUE(transport.Publish(channel, bytes.data(), bytes.size()));
}

// Publishes a map and waits (up to 5 s) until the core has read one: maps are read on a
// thread of their own, and requests sent before it is done get no_map.
void PublishMapAndWait(LcmTransport& transport, const DaemonCore& core, const std::string& name) {
  Publish(transport, kTerrainMapChannel, Encode(MapMessage(name)));
  for (int i = 0; i < 500 && core.counters().maps == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
}

// Replies collected from memq://, by request id.
struct ReplyCollector {
  explicit ReplyCollector(LcmTransport& transport) {
    transport.Subscribe(kPlanChannel, [this](const RawMessage& raw) {
      plan_t m;
      ASSERT_EQ(DecodeGuarded(raw.data, raw.size, 1 << 20, &m), "");
      std::lock_guard<std::mutex> lock(mutex);
      ++replies[m.request_id];
      ++by_status[m.status];
    });
  }
  size_t distinct() {
    std::lock_guard<std::mutex> lock(mutex);
    return replies.size();
  }
  std::mutex mutex;
  std::map<int64_t, int> replies;
  std::map<int, int> by_status;
};

TEST(DaemonRunnerTest, ABurstOf2000RequestsIsAnsweredOnceEach) {
  LcmTransport transport("memq://", 4096);
  auto setup = TestSetup(4);
  const RobotModel& hexapod = setup->robots.at("hexapod");
  DaemonCore core(setup, FakeMap, FakePlan, transport, &SteadyUs);
  core.SubscribeTo(transport);
  ReplyCollector collector(transport);
  DaemonRunner runner(core, transport, 0.2);
  PublishMapAndWait(transport, core, "flat");
  constexpr int kBurst = 2000;
  for (int id = 1; id <= kBurst; ++id) Publish(transport, kPlanRequestChannel, Encode(Request(hexapod, id)));
  for (int i = 0; i < 1000 && collector.distinct() < kBurst; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  runner.Stop();
  std::lock_guard<std::mutex> lock(collector.mutex);
  EXPECT_EQ(collector.replies.size(), static_cast<size_t>(kBurst));
  for (const auto& entry : collector.replies) EXPECT_EQ(entry.second, 1) << entry.first;
  const DaemonCounters c = core.counters();
  EXPECT_EQ(c.requests, kBurst);
  EXPECT_EQ(c.plans, kBurst);
  EXPECT_GT(c.superseded_requests, 0);
  EXPECT_EQ(collector.by_status[plan_t::STATUS_SUPERSEDED], c.superseded_requests);
}

// Threads of this process now (/proc/self/status), -1 when unknown.
int ThreadCount() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("Threads:", 0) == 0) return std::stoi(line.substr(8));
  }
  return -1;
}

TEST(DaemonRunnerTest, ABurstAgainstSlowPlansKeepsThreadsBoundedAndAnswersOnceEach) {
  LcmTransport transport("memq://", 4096);
  auto setup = std::make_shared<DaemonSetup>(*TestSetup(4, /*supersede=*/false));
  const RobotModel& hexapod = setup->robots.at("hexapod");
  auto planner = std::make_shared<StubbornPlanner>();
  planner->wind_down = std::chrono::milliseconds(400);
  DaemonCore core(setup, FakeMap,
                  [planner](const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                            const PlanRequest& request, const PlannerOptions& options) {
                    return (*planner)(robot, regions, request, options);
                  },
                  transport, &SteadyUs);
  core.SubscribeTo(transport);
  ReplyCollector collector(transport);
  DaemonRunner runner(core, transport, 0.2);
  PublishMapAndWait(transport, core, "flat");
  const int threads_before = ThreadCount();
  ASSERT_GT(threads_before, 0);
  int most_threads = threads_before;
  constexpr int kBurst = 100;
  for (int id = 1; id <= kBurst; ++id) {
    plan_request_t request = Request(hexapod, id);
    request.time_limit_s = 0.05;
    Publish(transport, kPlanRequestChannel, Encode(request));
    std::this_thread::sleep_for(std::chrono::milliseconds(10));  // 100 Hz
    most_threads = std::max(most_threads, ThreadCount());
  }
  for (int i = 0; i < 500 && collector.distinct() < kBurst; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    most_threads = std::max(most_threads, ThreadCount());
  }
  runner.Stop();
  while (transport.HandleTimeout(50) > 0) {
  }
  // The plan being waited for and the abandoned ones, no more.
  EXPECT_LE(most_threads, threads_before + setup->config.limits.max_abandoned_plans);
  EXPECT_LE(planner->most.load(), setup->config.limits.max_abandoned_plans);
  std::lock_guard<std::mutex> lock(collector.mutex);
  EXPECT_EQ(collector.replies.size(), static_cast<size_t>(kBurst));
  for (const auto& entry : collector.replies) EXPECT_EQ(entry.second, 1) << entry.first;
  EXPECT_GT(collector.by_status[plan_t::STATUS_DROPPED], 0);
}

TEST(DaemonRunnerTest, StopDuringAMapExtractionReturnsPromptlyAndAnswersEveryRequest) {
  LcmTransport transport("memq://", 4096);
  auto setup = TestSetup(4);
  const RobotModel& hexapod = setup->robots.at("hexapod");
  auto slow_map = [](const std::string& bytes, const std::string& format, const std::string& what) {
    if (bytes == "slow") std::this_thread::sleep_for(std::chrono::seconds(5));
    return FakeMap("flat", format, what);
  };
  DaemonCore core(setup, slow_map, SleepyPlan, transport, &SteadyUs);
  core.SubscribeTo(transport);
  ReplyCollector collector(transport);
  DaemonRunner runner(core, transport, 0.2);
  PublishMapAndWait(transport, core, "flat");
  Publish(transport, kTerrainMapChannel, Encode(MapMessage("slow")));
  plan_request_t request = Request(hexapod, 1);
  request.time_limit_s = 10;
  Publish(transport, kPlanRequestChannel, Encode(request));  // planned by the 3 s planner
  plan_request_t dog = Request(setup->robots.at("littledog"), 2);
  dog.robot = "littledog";
  Publish(transport, kPlanRequestChannel, Encode(dog));  // queued behind it
  for (int i = 0; i < 500 && !(core.StatusMessage().extracting_map &&
                               core.StatusMessage().state == status_t::STATE_PLANNING);
       ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(core.StatusMessage().extracting_map);
  const auto start = std::chrono::steady_clock::now();
  runner.Stop();
  EXPECT_LT(SecondsSince(start), 0.5);
  // memq:// delivers on the handling thread, which the runner has stopped.
  while (transport.HandleTimeout(50) > 0) {
  }
  std::lock_guard<std::mutex> lock(collector.mutex);
  EXPECT_EQ(collector.replies.size(), 2u);
  EXPECT_EQ(collector.by_status[plan_t::STATUS_DROPPED], 2);
}

TEST(DaemonConfigTest, IntakeAndLcmBuffersComeFromTheConfig) {
  const DaemonConfig config = LoadDaemonConfig(std::string(MFP_SOURCE_DIR) + "/config/daemon.yaml");
  EXPECT_EQ(config.lcm_queue_capacity, 4096);
  // 0 in the file: the largest accepted map and a MiB more.
  EXPECT_EQ(config.lcm_recv_buf_bytes, config.limits.max_map_bytes + (1u << 20));
  EXPECT_TRUE(config.limits.supersede_same_robot);
  EXPECT_FALSE(config.limits.accept_empty_maps);
  EXPECT_EQ(WithReceiveBuffer("udpm://239.255.76.67:7667?ttl=0", 1000),
            "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=1000");
  EXPECT_EQ(WithReceiveBuffer("udpm://239.255.76.67:7667", 1000),
            "udpm://239.255.76.67:7667?recv_buf_size=1000");
  EXPECT_EQ(WithReceiveBuffer("udpm://h:1?recv_buf_size=5", 1000), "udpm://h:1?recv_buf_size=5");
  EXPECT_EQ(WithReceiveBuffer("memq://", 1000), "memq://");

  // A config with the hexapod and `rest` is refused with a message containing `names`.
  const std::string path = TestTempPath("daemon.yaml");
  auto expect_refused = [&](const std::string& rest, const std::string& names) {
    {
      std::ofstream out(path);
      out << "robots: [" << MFP_SOURCE_DIR << "/config/robots/hexapod.yaml]\n" << rest;
    }
    try {
      LoadDaemonConfig(path);
      ADD_FAILURE() << "accepted: " << rest;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(names), std::string::npos) << e.what();
    }
  };
  expect_refused("lcm_queue_capacity: 0\n", "lcm_queue_capacity");
  // A key that was removed says what replaced it.
  expect_refused("limits:\n  start_height_tolerance_m: 0.05\n", "planner.start_tolerance");
  // The requests' defaults come from limits:, so the planner's keys of the same meaning,
  // which they would silently replace, are refused naming the key that wins.
  expect_refused("planner:\n  time_limit: 3\n", "limits.default_time_limit_s");
  expect_refused("planner:\n  max_steps: 30\n", "limits.default_max_steps");
  EXPECT_TRUE(config.warnings.empty());  // the shipped config uses the sections
  EXPECT_EQ(config.planner.branch_and_bound.max_nodes, 20000);
  EXPECT_DOUBLE_EQ(config.planner.default_time_limit_s, config.limits.default_time_limit_s);
  std::remove(path.c_str());
}

// The live runner over memq://: bad payloads and invalid requests, then a valid one
// planned by a slow planner while the heartbeat keeps going.
TEST(DaemonRunnerTest, SurvivesBadInputOverMemqAndKeepsTheHeartbeat) {
  LcmTransport transport("memq://");
  auto setup = TestSetup(4);
  const RobotModel& hexapod = setup->robots.at("hexapod");
  auto slow_plan = [](const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                      const PlanRequest& request, const PlannerOptions& options) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    return FakePlan(robot, regions, request, options);
  };
  auto clock = [] {
    return std::chrono::duration_cast<std::chrono::microseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
  };
  DaemonCore core(setup, FakeMap, slow_plan, transport, clock);
  core.SubscribeTo(transport);

  std::mutex mutex;
  std::vector<plan_t> replies;
  std::vector<status_t> statuses;
  transport.Subscribe(kPlanChannel, [&](const RawMessage& raw) {
    plan_t m;
    ASSERT_EQ(DecodeGuarded(raw.data, raw.size, 1 << 20, &m), "");
    std::lock_guard<std::mutex> lock(mutex);
    replies.push_back(m);
  });
  transport.Subscribe(kStatusChannel, [&](const RawMessage& raw) {
    status_t m;
    ASSERT_EQ(DecodeGuarded(raw.data, raw.size, 1 << 20, &m), "");
    std::lock_guard<std::mutex> lock(mutex);
    statuses.push_back(m);
  });
  DaemonRunner runner(core, transport, 0.2);

  PublishMapAndWait(transport, core, "flat");
  ASSERT_EQ(core.counters().maps, 1);
  const auto bad = BadPayloads(hexapod);
  for (const auto& payload : bad) Publish(transport, kPlanRequestChannel, payload);
  for (const auto& payload : bad) Publish(transport, kTerrainMapChannel, payload);
  plan_request_t wrong_legs = Request(hexapod, 1);
  wrong_legs.num_legs = 3;
  wrong_legs.start_feet.resize(3);
  Publish(transport, kPlanRequestChannel, Encode(wrong_legs));
  plan_request_t nan_goal = Request(hexapod, 2);
  nan_goal.goal_yaw = std::nan("");
  Publish(transport, kPlanRequestChannel, Encode(nan_goal));
  plan_request_t valid = Request(hexapod, 3);
  valid.time_limit_s = 5.0;  // more than the slow planner's 1.5 s
  Publish(transport, kPlanRequestChannel, Encode(valid));

  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  size_t heartbeats_while_planning = 0;
  for (;;) {
    {
      std::lock_guard<std::mutex> lock(mutex);
      heartbeats_while_planning = 0;
      for (const status_t& s : statuses)
        if (s.state == status_t::STATE_PLANNING) ++heartbeats_while_planning;
      if (replies.size() >= 3) break;
    }
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "no reply to the valid request";
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  runner.Stop();
  std::lock_guard<std::mutex> lock(mutex);
  ASSERT_EQ(replies.size(), 3u);
  EXPECT_EQ(replies[0].request_id, 1);
  EXPECT_EQ(replies[0].status, +plan_t::STATUS_INVALID_REQUEST);
  EXPECT_EQ(replies[1].request_id, 2);
  EXPECT_NE(replies[1].message.find("goal_yaw"), std::string::npos);
  EXPECT_EQ(replies[2].request_id, 3);
  EXPECT_EQ(replies[2].status, +plan_t::STATUS_OPTIMAL);
  // The 1.5 s plan ran on the worker; the 0.2 s heartbeat went on meanwhile.
  EXPECT_GE(heartbeats_while_planning, 4u);
  const DaemonCounters c = core.counters();
  // A bad map still waiting when a newer one arrives is replaced unread (counted).
  EXPECT_EQ(c.rejected_messages + c.superseded_maps, static_cast<int64_t>(2 * bad.size()));
  EXPECT_EQ(c.invalid_requests, 2);
  EXPECT_EQ(c.plans, 3);
}

}  // namespace
}  // namespace mfp
