// mfp-check-replies: checks the daemon's replies recorded in an LCM log (lcm-logger or
// mfp-replay) against the scenario the requests came from: one plan_t per request id,
// the expected status and message, plans valid constraint by constraint on the
// published regions, status_t counters that account for every malformed payload.
// Exit 0 when every check passes, 1 otherwise, 3 when some request has no reply yet,
// 2 on bad input.
#include "io/cli_parse.h"
#include "lcmtypes/event_log_reader.h"

#include <CLI/CLI.hpp>
#include <iostream>
#include <map>
#include <sstream>

#include "base/check.h"
#include "daemon/daemon_config.h"
#include "daemon/daemon_setup.h"
#include "daemon/message_conversion.h"
#include "daemon/replay_scenario.h"
#include "lcmtypes/message_guard.h"
#include "mfp/plan_t.hpp"
#include "mfp/region_set_t.hpp"
#include "mfp/status_t.hpp"
#include "planner/planning/plan_validation.h"

namespace mfp {
namespace {

constexpr size_t kMaxReplyBytes = 256u << 20;
// Exit status when some request has no reply yet (a caller may wait and check again).
constexpr int kExitIncomplete = 3;

struct Recorded {
  std::vector<plan_t> plans;
  std::vector<size_t> region_sets_before;  // per plan: region sets received before it
  std::vector<region_set_t> region_sets;
  std::vector<status_t> statuses;
  int undecodable = 0;
};

Recorded ReadLog(const std::string& path) {
  EventLogReader log(path, kMaxReplyBytes);
  Recorded r;
  LogEvent e;
  while (log.Next(&e)) {
    const std::string& channel = e.channel;
    const uint8_t* data = e.data.data();
    const size_t size = e.data.size();
    std::string error;
    if (channel == kPlanChannel) {
      plan_t m;
      if ((error = DecodeGuarded(data, size, kMaxReplyBytes, &m)).empty()) {
        r.plans.push_back(m);
        r.region_sets_before.push_back(r.region_sets.size());
      }
    } else if (channel == kRegionsChannel) {
      region_set_t m;
      if ((error = DecodeGuarded(data, size, kMaxReplyBytes, &m)).empty()) r.region_sets.push_back(m);
    } else if (channel == kStatusChannel) {
      status_t m;
      if ((error = DecodeGuarded(data, size, kMaxReplyBytes, &m)).empty()) r.statuses.push_back(m);
    }
    if (!error.empty()) {
      std::cout << "undecodable " << channel << " event: " << error << "\n";
      ++r.undecodable;
    }
  }
  return r;
}

class Checker {
 public:
  void Fail(const std::string& what) {
    std::cout << "FAIL " << what << "\n";
    ++failures_;
  }
  void Ok(const std::string& what) { std::cout << "ok   " << what << "\n"; }
  int failures() const { return failures_; }

 private:
  int failures_ = 0;
};

std::string Describe(const plan_t& p) {
  std::ostringstream out;
  out << "request " << p.request_id << ": " << ToString(static_cast<SolveStatus>(p.status)) << ", "
      << p.num_steps << " footsteps";
  if (p.num_steps > 0) out << (p.reaches_goal ? ", reaches the goal" : ", short of the goal");
  out << ", " << p.solve_time_s << " s";
  if (!p.message.empty()) out << " (" << p.message << ")";
  return out.str();
}

int Run(const std::string& log_path, const std::string& scenario_path, const std::string& config_path) {
  const ReplayScenario scenario = LoadReplayScenario(scenario_path);
  const DaemonSetup setup = LoadDaemonSetup(LoadDaemonConfig(config_path));
  const Recorded recorded = ReadLog(log_path);
  Checker check;
  if (recorded.undecodable > 0) check.Fail(std::to_string(recorded.undecodable) + " undecodable replies");
  bool plans_expected = false;
  for (const ScenarioRequest& r : scenario.requests)
    plans_expected = plans_expected || r.expect == "plan" || r.expect == "reaches_goal";
  if (recorded.region_sets.empty()) {
    // Plans are checked on the regions; without expected plans none may have been sent
    // (a map still being read, say).
    if (plans_expected) check.Fail("no region_set_t on MFP_REGIONS");
  } else {
    check.Ok(std::to_string(recorded.region_sets.size()) + " region set(s), last with " +
             std::to_string(recorded.region_sets.back().num_regions) + " regions");
  }
  // A reply is checked on the region set last published before it (a plan on footholds is
  // preceded by its map's set with them added); one before any set, on the last set.
  std::map<size_t, std::vector<ConvexRegion>> regions_of_set;
  const std::vector<ConvexRegion> no_regions;
  auto regions_for = [&](const plan_t& p) -> const std::vector<ConvexRegion>& {
    if (recorded.region_sets.empty()) return no_regions;
    const size_t before = recorded.region_sets_before[static_cast<size_t>(&p - recorded.plans.data())];
    const size_t index = before > 0 ? before - 1 : recorded.region_sets.size() - 1;
    auto it = regions_of_set.find(index);
    if (it == regions_of_set.end()) {
      it = regions_of_set.emplace(index, FromRegionSetMessage(recorded.region_sets[index])).first;
    }
    return it->second;
  };

  std::map<int64_t, std::vector<const plan_t*>> replies;
  for (const plan_t& p : recorded.plans) replies[p.request_id].push_back(&p);
  std::map<int64_t, const ScenarioRequest*> requests;
  for (const ScenarioRequest& r : scenario.requests) requests[r.id] = &r;
  for (const auto& [id, list] : replies) {
    if (requests.count(id) == 0) check.Fail("reply to unknown request id " + std::to_string(id));
  }

  int unanswered = 0;
  for (const ScenarioRequest& r : scenario.requests) {
    const auto found = replies.find(r.id);
    if (found == replies.end()) ++unanswered;
    const size_t count = found == replies.end() ? 0 : found->second.size();
    if (count != 1) {
      check.Fail("request " + std::to_string(r.id) + ": " + std::to_string(count) +
                 " replies, expected exactly 1");
      continue;
    }
    const plan_t& p = *found->second.front();
    const SolveStatus status = static_cast<SolveStatus>(p.status);
    std::vector<std::string> problems;
    if (r.expect == "plan" || r.expect == "reaches_goal") {
      if (!HasPlan(status)) problems.push_back("expected a plan");
      if (r.expect == "reaches_goal" && !p.reaches_goal)
        problems.push_back("expected a plan that reaches the goal");
      const auto robot = setup.robots.find(p.robot);
      if (robot == setup.robots.end()) {
        problems.push_back("reply names unknown robot '" + p.robot + "'");
      } else if (HasPlan(status)) {
        Plan plan;
        plan.status = status;
        plan.reaches_goal = p.reaches_goal;
        plan.footsteps = FootstepsFromPlanMessage(p);
        GoalSpec goal;
        goal.x_m = r.goal.x();
        goal.y_m = r.goal.y();
        goal.yaw_rad = r.goal.z();
        goal.tolerance_m = setup.config.planner.goal_tolerance_m;
        goal.yaw_tolerance_rad = setup.config.planner.goal_yaw_tolerance_rad;
        // Exact trigonometry, as mfp-plan --validate: each footstep's own yaw, no slack for chords.
        for (const std::string& issue : ValidatePlan(robot->second, regions_for(p), plan, goal, ValidationTolerances{}))
          problems.push_back(issue);
      }
    } else if (ToString(status) != r.expect) {
      problems.push_back("expected status " + r.expect);
    }
    if (!r.expect_message.empty() && p.message.find(r.expect_message) == std::string::npos)
      problems.push_back("message does not name '" + r.expect_message + "'");
    if (problems.empty()) {
      check.Ok(Describe(p));
    } else {
      std::string all;
      for (const std::string& issue : problems) all += "\n       " + issue;
      check.Fail(Describe(p) + all);
    }
  }

  if (recorded.statuses.empty()) {
    check.Fail("no status_t on MFP_STATUS");
  } else {
    const status_t& last = recorded.statuses.back();
    std::ostringstream line;
    line << recorded.statuses.size() << " status messages; last: " << last.message;
    const auto malformed = static_cast<int64_t>(scenario.malformed.size());
    const auto sent = static_cast<int64_t>(scenario.requests.size());
    if (last.rejected_messages < malformed) {
      check.Fail(line.str() + " -- expected at least " + std::to_string(malformed) + " rejected messages");
    } else if (last.requests != sent || last.plans != static_cast<int64_t>(recorded.plans.size())) {
      check.Fail(line.str() + " -- expected " + std::to_string(sent) + " requests and " +
                 std::to_string(recorded.plans.size()) + " plans");
    } else {
      check.Ok(line.str());
    }
  }
  std::cout << (check.failures() == 0 ? "all checks passed" : std::to_string(check.failures()) + " check(s) failed")
            << "\n";
  if (check.failures() == 0) return 0;
  return unanswered > 0 ? kExitIncomplete : 1;
}

}  // namespace
}  // namespace mfp

int main(int argc, char** argv) {
  CLI::App app{"mfp-check-replies: checks recorded daemon replies against a scenario"};
  std::string log, scenario, config = "config/daemon.yaml";
  app.add_option("log", log, "LCM log with the daemon's replies")->required();
  app.add_option("--scenario", scenario, "the scenario the requests came from")->required();
  app.add_option("--config", config, "daemon YAML: robots and tolerances")->capture_default_str();
  MFP_CLI_PARSE(app, argc, argv);
  try {
    return mfp::Run(log, scenario, config);
  } catch (const mfp::InputError& e) {
    std::cerr << "mfp-check-replies: " << e.what() << "\n";
    return 2;
  }
}
