// YAML of any shape is an input error naming the problem, never an abort: keys that are
// lists or mappings, lists where mappings belong and back, any bytes in strings, deep
// nesting, aliases. Each loader a user or the daemon's SIGHUP reaches is fed each shape.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <string>

#include "base/check.h"
#include "io/robot_yaml.h"
#include "io/scenario_yaml.h"
#include "io/terrain_yaml.h"
#include "test_temp_path.h"

namespace mfp {
namespace {

const std::string kRobot = std::string(MFP_SOURCE_DIR) + "/config/robots/hexapod.yaml";

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = TestTempPath(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// Loading must either succeed or throw InputError whose message contains `expect`.
void ExpectInputError(const std::function<void()>& load, const std::string& expect) {
  try {
    load();
    ADD_FAILURE() << "loaded without error; expected one naming '" << expect << "'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
  }
}

std::string Scenario(const std::string& top, const std::string& terrain_extra,
                     const std::string& planner) {
  return "robot: " + kRobot + "\n" + top +
         "terrain:\n  resolution: 0.02\n" + terrain_extra +
         "  boxes:\n    - {center: [0, 0, -0.05], size: [2, 2, 0.1]}\n"
         "start: [0, 0, 0]\ngoal: [0.5, 0, 0]\n" + planner;
}

TEST(HostileYaml, KeyThatIsAListOrMappingInAScenario) {
  struct Case { std::string top, terrain, planner, expect; };
  const Case cases[] = {
      {"? [a, b]\n: 1\n", "", "", "a key is a list"},
      {"? {a: 1}\n: 1\n", "", "", "a key is a mapping"},
      {"", "  ? [a, b]\n  : 1\n", "", "terrain: a key is a list"},
      {"", "", "planner:\n  ? [a, b]\n  : 1\n", "planner: a key is a list"},
      {"", "", "planner:\n  ? {x: [1]}\n  : 1\n", "planner: a key is a mapping"},
  };
  for (const Case& c : cases) {
    const std::string path = Write("scenario.yaml", Scenario(c.top, c.terrain, c.planner));
    ExpectInputError([&] { LoadScenario(path); }, c.expect);
    if (!c.terrain.empty()) ExpectInputError([&] { LoadTerrainDescription(path); }, c.expect);
  }
}

TEST(HostileYaml, KeyThatIsAListInARobotYaml) {
  ExpectInputError([&] { LoadRobotYaml(Write("r.yaml", "urdf: x.urdf\n? [a, b]\n: 1\n")); },
                   "a key is a list");
  ExpectInputError(
      [&] {
        LoadRobotYaml(Write("r.yaml", "legs:\n  - nominal_offset: [0, 0]\n    ? [a]\n    : 1\n"));
      },
      "legs[0]: a key is a list");
}

// An empty file, or one of comments only, says so (not just "expected a mapping") and
// where the keys are listed, for every loader of a file a user writes.
TEST(HostileYaml, AnEmptyFileSaysItIsEmptyAndWhereTheKeysAreListed) {
  for (const std::string text : {"", "# only a comment\n", "\n\n"}) {
    const std::string path = Write("empty.yaml", text);
    ExpectInputError([&] { LoadScenario(path); }, "empty.yaml: the file is empty (or comments only)");
    ExpectInputError([&] { LoadTerrainDescription(path); }, "the file is empty");
    ExpectInputError([&] { LoadRobotYaml(path); }, "docs/options.md");
  }
}

TEST(HostileYaml, WrongKindsAnywhere) {
  // Each a node of the wrong kind where the loader subscripts or reads it.
  const std::string wrong[] = {
      "[1, 2]\n",                       // top level a list
      "just a string\n",                // top level a scalar
      "robot: [a, b]\n",                // a list where a path belongs
      "robot: x\nterrain: 5\nstart: [0,0,0]\ngoal: [1,0,0]\n",
      "robot: x\nterrain: [1]\nstart: [0,0,0]\ngoal: [1,0,0]\n",
      "robot: x\nterrain: {boxes: {a: 1}}\nstart: [0,0,0]\ngoal: [1,0,0]\n",
      "robot: x\nterrain: {boxes: [5]}\nstart: [0,0,0]\ngoal: [1,0,0]\n",
      "robot: x\nterrain: {regions: {a: 1}}\nstart: [0,0,0]\ngoal: [1,0,0]\n",
      "robot: x\nterrain: {regions: [[1, [2]]]}\nstart: [0,0,0]\ngoal: [1,0,0]\n",
      "robot: x\nterrain: {map: [1]}\nstart: [0,0,0]\ngoal: [1,0,0]\n",
      "robot: x\nterrain: {boxes: []}\nstart: {x: 1}\ngoal: [1,0,0]\n",
      "robot: x\nterrain: {boxes: []}\nstart: [0,0,0]\ngoal: [1,0,0]\nplanner: [1]\n",
      "robot: x\nterrain: {boxes: []}\nstart: [0,0,0]\ngoal: [1,0,0]\nplanner: {max_steps: [1]}\n",
      "a: &x [*x]\n",                   // an alias to itself
      "robot: x\nterrain: {boxes: []}\nstart: [0,0,0]\ngoal: [1,0,0]\nmax_steps: !!binary AAAA\n",
  };
  for (const std::string& text : wrong) {
    const std::string path = Write("scenario.yaml", text);
    ExpectInputError([&] { LoadScenario(path); }, path);
    ExpectInputError([&] { LoadRobotYaml(path); }, path);
  }
}

TEST(HostileYaml, DeepNestingIsAnErrorNotAStackOverflow) {
  const std::string deep = "a: " + std::string(100000, '[') + "\n";
  const std::string path = Write("deep.yaml", deep);
  ExpectInputError([&] { LoadScenario(path); }, path);
}

TEST(HostileYaml, StringsOfAnyBytes) {
  // A robot name with NUL, invalid UTF-8 and control bytes: loads (a name is only
  // text) or is refused with a message; either way no abort.
  std::string name = "\"ro\\0bot\\x01";
  name += "\"";
  for (const std::string& value : {name, std::string("\xff\xfe\x80 raw"), std::string("'\x1b[31m'")}) {
    const std::string path = Write("r.yaml", "name: " + value + "\nlegs:\n  - nominal_offset: [0.2, 0.1]\n");
    try {
      LoadRobotYaml(path);
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace mfp

namespace mfp {
namespace {

TEST(HostileYaml, AnAliasBombOfRegionsIsRefusedBeforeItIsBuilt) {
  // One 1,000-vertex polygon named 2,000 times: a 30 KB file, 2 M vertices.
  std::string poly = "[";
  for (int k = 0; k < 1000; ++k) {
    const double a = 2 * M_PI * k / 1000;
    poly += (k ? ", " : "") + std::string("[") + std::to_string(std::cos(a)) + ", " +
            std::to_string(std::sin(a)) + ", 0]";
  }
  poly += "]";
  std::string text = "robot: " + kRobot + "\nstart: [0, 0, 0]\ngoal: [0.5, 0, 0]\nterrain:\n  regions:\n";
  text += "    - {vertices: &p " + poly + "}\n";
  for (int i = 0; i < 2000; ++i) text += "    - {vertices: *p}\n";
  const std::string path = Write("bomb.yaml", text);
  ExpectInputError([&] { LoadScenario(path); }, "vertices in all");
  // A polygon of too many vertices, once.
  std::string many = "[";
  for (int k = 0; k < 1001; ++k) many += (k ? ", " : "") + std::string("[0, 0, 0]");
  const std::string one = Write("one.yaml", "robot: " + kRobot + "\nstart: [0, 0, 0]\ngoal: [0.5, 0, 0]\n"
                                                 "terrain:\n  regions:\n    - {vertices: " + many + "]}\n");
  ExpectInputError([&] { LoadScenario(one); }, "regions[0].vertices: 1001 vertices");
}

}  // namespace
}  // namespace mfp
