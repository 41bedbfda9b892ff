// A small seeded fuzz harness over the decoders of user input: scenario and robot YAML,
// URDF, OctoMap maps (file bytes and region extraction), LCM payloads and LCM logs.
// Each case mutates a valid input (bytes flipped, YAML/XML syntax spliced in, spans cut,
// copied or repeated, lengths replaced by extreme values) and feeds it to the decoder.
// It must load, or throw InputError (or return a reason) that names the input and says
// something: never a signal, never another exception. Fixed seeds and case counts keep
// it a few seconds long and the same on every run; MFP_FUZZ_CASES scales the counts for
// a longer hunt by hand.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "base/check.h"
#include "io/robot_yaml.h"
#include "io/scenario_yaml.h"
#include "io/terrain_yaml.h"
#include "lcmtypes/event_log_reader.h"
#include "lcmtypes/message_guard.h"
#include "planner/robot/robot_derivation.h"
#include "planner/robot/urdf_reader.h"
#include "terrain/extraction/region_extractor.h"
#include "terrain/octomap/octomap_io.h"
#include "test_temp_path.h"

namespace mfp {
namespace {

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string Source(const std::string& rel) { return std::string(MFP_SOURCE_DIR) + "/" + rel; }

int Cases(int base) {
  const char* scale = std::getenv("MFP_FUZZ_CASES");
  return scale != nullptr ? base * std::max(1, std::atoi(scale)) : base;
}

// One mutation of `text`, chosen by rng: the fragments are syntax of the input's format.
std::string Mutate(std::string text, std::mt19937& rng, const std::vector<std::string>& fragments) {
  const int edits = 1 + static_cast<int>(rng() % 4);
  for (int e = 0; e < edits; ++e) {
    if (text.empty()) text = "x";
    const size_t at = rng() % text.size();
    const size_t span = std::min<size_t>(text.size() - at, 1 + rng() % 64);
    switch (rng() % 7) {
      case 0: text[at] = static_cast<char>(rng() % 256); break;          // any byte
      case 1: text.insert(at, fragments[rng() % fragments.size()]); break;  // syntax
      case 2: text.erase(at, span); break;                                  // cut
      case 3: text.insert(at, text.substr(rng() % text.size(), span)); break;  // copy
      case 4: text.resize(at); break;                                       // truncate
      case 5: text.insert(at, std::string(1 + rng() % 200, "[{<&*!?-:\"'\\\n\0"[rng() % 15])); break;
      default: {  // a number replaced by an extreme one
        static const char* extremes[] = {"1e308", "-1e308", "nan", "inf", "-0", "2147483648",
                                         "-2147483649", "1e-320", "0x7fffffff", "99999999999999999999"};
        text.insert(at, extremes[rng() % 10]);
      }
    }
  }
  return text;
}

// Runs load(); fails unless it returns or throws InputError whose message contains one
// of `names` (the input's path; a file the input refers to) and says more than that.
// Counts the errors.
void ExpectLoadsOrNamesTheProblem(const std::function<void()>& load, const std::vector<std::string>& names,
                                  const std::string& input, int* errors) {
  try {
    load();
  } catch (const InputError& e) {
    ++*errors;
    const std::string what = e.what();
    const std::string* named = nullptr;
    for (const std::string& name : names) {
      if (named == nullptr && what.find(name) != std::string::npos) named = &name;
    }
    ASSERT_NE(named, nullptr) << what << "\ninput:\n" << input;
    EXPECT_GT(what.size(), named->size() + 8) << what;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an InputError: " << e.what() << "\ninput:\n" << input;
  }
}

const std::vector<std::string> kYamlFragments = {
    "? [a, b]\n: 1\n", "? {a: 1}\n: 2\n", "{", "}", "[", "]", ": ", "- ", "&a ", "*a ", "!!binary ",
    "!!map ", "'", "\"", "\\x00", "\n  ", "\t", "---\n", "...\n", "<<: *a\n", "%YAML 1.2\n",
    "planner: {max_steps: [1]}\n", "terrain: 5\n", "legs: {a: 1}\n", "name: \xff\xfe\n"};

TEST(FuzzDecoders, ScenarioAndRobotYaml) {
  const std::string seeds[] = {ReadFile(Source("config/scenarios/hexapod_stepping_stones_45.yaml")),
                               ReadFile(Source("config/robots/hexapod.yaml")),
                               ReadFile(Source("config/robots/littledog.yaml"))};
  std::mt19937 rng(19);
  const std::string path = TestTempPath("fuzz.yaml");
  // A robot YAML's urdf: is resolved next to it: a missing URDF is named in this folder.
  const std::string folder = std::filesystem::path(path).parent_path().string();
  int errors = 0, cases = 0;
  for (int i = 0; i < Cases(150); ++i) {
    for (const std::string& seed : seeds) {
      const std::string text = Mutate(seed, rng, kYamlFragments);
      // The robot path of the scenario stays absolute, so a loaded scenario means nothing
      // outside this file was trusted; the robot YAML's urdf: is relative to `path`,
      // which has no URDF beside it (an error naming the path).
      std::ofstream(path, std::ios::binary) << text;
      ++cases;
      ExpectLoadsOrNamesTheProblem([&] { LoadScenario(path); }, {path}, text, &errors);
      ExpectLoadsOrNamesTheProblem([&] { LoadTerrainDescription(path); }, {path}, text, &errors);
      ExpectLoadsOrNamesTheProblem([&] { LoadRobotYaml(path); }, {path, folder}, text, &errors);
    }
  }
  EXPECT_GT(errors, cases);  // most mutations break something: the harness does reach errors
}

TEST(FuzzDecoders, Urdf) {
  const std::vector<std::string> fragments = {
      "<", ">", "</", "/>", "<joint name=\"j\" type=\"revolute\">", "<link name=\"x\"/>",
      "<!ENTITY a \"aaaaaaaaaa\">", "&a;", "<![CDATA[", "]]>", "<!--", "-->", "xyz=\"1 2\"",
      "type=\"continuous\"", "type=\"floating\"", "<axis xyz=\"0 0 0\"/>", "\"", "="};
  const std::string seed = ReadFile(Source("config/robots/littledog.urdf"));
  std::mt19937 rng(15);
  const std::string path = TestTempPath("fuzz.urdf");
  int errors = 0;
  for (int i = 0; i < Cases(200); ++i) {
    const std::string text = Mutate(seed, rng, fragments);
    std::ofstream(path, std::ios::binary) << text;
    ExpectLoadsOrNamesTheProblem([&] { ReadUrdfRobot(path); }, {path}, text, &errors);
  }
  EXPECT_GT(errors, 50);
}

// Issue 27: every number of a URDF, one at a time, at +-1e308 (finite, so the finite
// check passes it): read and derived, it must load or be an InputError, never bad_alloc
// from a grid sized by an overflowed extent. The derivation runs on small grids: the
// grids are sized by the same code at any resolution.
TEST(FuzzDecoders, UrdfNumbersAtTheEdgeOfDouble) {
  const std::string seed = ReadFile(Source("tests/data/robots/sphere_quad.urdf"));
  const std::string path = TestTempPath("extreme.urdf");
  DerivationOptions quick;
  quick.samples_per_leg = 500;
  quick.final_cells = 16;
  quick.scan_cells = 6;
  quick.stance_candidates = 3;
  int numbers = 0, errors = 0;
  for (size_t open = seed.find("=\""); open != std::string::npos; open = seed.find("=\"", open + 1)) {
    const size_t begin = open + 2, end = seed.find('"', begin);
    for (size_t at = begin; at < end;) {
      const size_t stop = std::min(end, seed.find(' ', at));
      char* parsed = nullptr;
      const std::string token = seed.substr(at, stop - at);
      std::strtod(token.c_str(), &parsed);
      if (!token.empty() && parsed == token.c_str() + token.size()) {
        ++numbers;
        for (const char* extreme : {"1e308", "-1e308"}) {
          std::string text = seed;
          text.replace(at, stop - at, extreme);
          std::ofstream(path, std::ios::binary) << text;
          ExpectLoadsOrNamesTheProblem([&] { DeriveRobot(ReadUrdfRobot(path), quick); }, {path, "footprint"},
                                       text, &errors);
        }
      }
      at = stop + 1;
    }
  }
  EXPECT_GT(numbers, 200);   // every number of the file was reached
  EXPECT_GT(errors, numbers);  // and most extremes refused (angles may stay finite)
}

TEST(FuzzDecoders, OctomapBytesAndRegionExtraction) {
  // A small map of a few boxes, written by mfp itself, mutated.
  const std::string bt = TestTempPath("seed.bt");
  WriteTerrainMap(LoadTerrainDescription(Source("config/scenarios/littledog_stepping_stones_45.yaml")), bt);
  const std::string seed = ReadFile(bt);
  const std::vector<std::string> fragments = {"res 0.0001\n", "res 1e308\n", "size 4294967296\n",
                                              "id ColorOcTree\n", "data\n", "\xff\xff\xff\xff",
                                              std::string(8, '\0'), "# comment\n"};
  std::mt19937 rng(16);
  int errors = 0, loaded = 0;
  RegionExtractorOptions options;
  for (int i = 0; i < Cases(120); ++i) {
    // Half the cases flip one byte of the tree data only: many of those still load and
    // reach the extractor.
    std::string text = seed;
    if (i % 2 == 0) {
      const size_t data = seed.find("data\n") + 5;
      text[data + rng() % (seed.size() - data)] ^= static_cast<char>(1 + rng() % 255);
    } else {
      text = Mutate(seed, rng, fragments);
    }
    const std::vector<uint8_t> bytes(text.begin(), text.end());
    ExpectLoadsOrNamesTheProblem(
        [&] {
          const OccupancyMap map = LoadMapBytes(bytes, "fuzz map", OctreeStreamLimits());
          ++loaded;
          options.deadline = Deadline::After(2.0);  // a mutation may make a big tree
          const RegionExtractionResult r = ExtractRegions(map, options);
          for (const ConvexRegion& region : r.regions) EXPECT_TRUE(region.A.allFinite());
        },
        {"fuzz map"}, text.substr(0, 200), &errors);
  }
  EXPECT_GT(errors, 20);
  EXPECT_GT(loaded, 0);
}

template <class Message>
void FuzzPayload(const Message& valid, unsigned seed, int cases, size_t max_bytes) {
  std::vector<uint8_t> bytes(static_cast<size_t>(valid.getEncodedSize()));
  ASSERT_EQ(valid.encode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
  std::mt19937 rng(seed);
  int rejected = 0;
  for (int i = 0; i < cases; ++i) {
    std::vector<uint8_t> b = bytes;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits && !b.empty(); ++e) {
      const size_t at = 8 + rng() % std::max<size_t>(1, b.size() - 8);  // keep the fingerprint mostly
      if (at >= b.size()) continue;
      switch (rng() % 5) {
        case 0: b[at] = static_cast<uint8_t>(rng()); break;
        case 1:  // a 32-bit length replaced by an extreme value
          for (int k = 0; k < 4 && at + k < b.size(); ++k) b[at + k] = (k == 0) ? (rng() % 2 ? 0x7f : 0x80) : 0xff;
          break;
        case 2: b.resize(at); break;
        case 3: b.insert(b.begin() + static_cast<std::ptrdiff_t>(at), rng() % 64, static_cast<uint8_t>(rng())); break;
        default: b[rng() % 8] ^= static_cast<uint8_t>(1 + rng() % 255); break;  // fingerprint
      }
    }
    Message out;
    const std::string reason = DecodeGuarded(b.data(), b.size(), max_bytes, &out);
    if (!reason.empty()) ++rejected;
  }
  EXPECT_GT(rejected, cases / 4);
}

TEST(FuzzDecoders, LcmPayloads) {
  plan_request_t request{};
  request.request_id = 7;
  request.robot = "hexapod";
  request.num_legs = 6;
  request.start_feet.assign(6, std::vector<double>(3, 0.1));
  FuzzPayload(request, 21, Cases(3000), 64 * 1024);
  terrain_map_t map{};
  map.format = "bt";
  map.num_bytes = 64;
  map.data.assign(64, 0x5a);
  FuzzPayload(map, 22, Cases(3000), 1 << 20);
}

TEST(FuzzDecoders, LcmLogs) {
  std::vector<uint8_t> seed;
  for (int k = 0; k < 5; ++k) {
    const std::vector<uint8_t> frame =
        EncodeLogFrame(k, 1000 * k, k % 2 ? "MFP_PLAN_REQUEST" : "MFP_TERRAIN_MAP", std::vector<uint8_t>(40 + k, 7));
    seed.insert(seed.end(), frame.begin(), frame.end());
  }
  std::mt19937 rng(23);
  const std::string path = TestTempPath("fuzz.lcmlog");
  int errors = 0;
  for (int i = 0; i < Cases(300); ++i) {
    const std::string text = Mutate(std::string(seed.begin(), seed.end()), rng,
                                    {"\x7f\xff\xff\xff", "\xff\xff\xff\xff", "\xed\xa1\xda\x01", std::string(4, '\0')});
    std::ofstream(path, std::ios::binary) << text;
    ExpectLoadsOrNamesTheProblem(
        [&] {
          EventLogReader reader(path, 1 << 20);
          LogEvent event;
          int events = 0;
          while (reader.Next(&event)) ASSERT_LE(++events, 1000);
        },
        {path}, "", &errors);
  }
  EXPECT_GT(errors, 60);
}

}  // namespace
}  // namespace mfp
