#include "bench/hostile_inputs.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace mfp {
namespace {

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

// The joint and link blocks of one octopod leg, in file order.
std::vector<std::string> LegBlocks(const std::string& text, const std::string& leg) {
  std::vector<std::string> blocks;
  const std::string joint = "<joint name=\"" + leg + "_", link = "<link name=\"" + leg + "_";
  size_t at = 0;
  for (;;) {
    const size_t j = text.find(joint, at), l = text.find(link, at);
    const size_t start = std::min(j, l);
    if (start == std::string::npos) break;
    const std::string close = start == j ? "</joint>" : "</link>";
    const size_t end = text.find(close, start);
    if (end == std::string::npos) break;
    blocks.push_back(text.substr(start, end + close.size() - start));
    at = end + close.size();
  }
  return blocks;
}

// block with every "leg_ name prefix renamed, and its first origin 3 cm lower when it
// is the leg's hip joint.
std::string CopiedBlock(std::string block, const std::string& leg) {
  const std::string from = "\"" + leg + "_", to = "\"" + leg + "b_";
  for (size_t at = block.find(from); at != std::string::npos; at = block.find(from, at + to.size())) {
    block.replace(at, from.size(), to);
  }
  if (block.find("_coxa_yaw\"") == std::string::npos) return block;
  const std::string origin = "<origin xyz=\"";
  const size_t at = block.find(origin);
  if (at == std::string::npos) return block;
  const size_t begin = at + origin.size(), end = block.find('"', begin);
  std::istringstream in(block.substr(begin, end - begin));
  double x = 0, y = 0, z = 0;
  in >> x >> y >> z;
  std::ostringstream out;
  out << x << ' ' << y << ' ' << z - 0.03;
  return block.replace(begin, end - begin, out.str());
}

}  // namespace

ChildRun ExecuteChild(const std::vector<std::string>& argv, double kill_after_s, const std::string& stderr_path) {
  std::fflush(nullptr);  // else the child's freopen writes the parent's buffered output again
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    if (!std::freopen(stderr_path.c_str(), "w", stderr) || !std::freopen("/dev/null", "w", stdout)) _exit(127);
    ::execv(args[0], args.data());
    _exit(127);
  }
  ChildRun run;
  int status = 0;
  struct rusage usage {};
  for (;;) {
    const pid_t done = ::wait4(pid, &status, WNOHANG, &usage);
    if (done == pid) break;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (elapsed > kill_after_s) ::kill(pid, SIGKILL);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  run.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.peak_bytes = static_cast<double>(usage.ru_maxrss) * 1024.0;  // ru_maxrss is in KiB
  if (WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) run.signal = WTERMSIG(status);
  std::ifstream in(stderr_path);
  run.err.assign(std::istreambuf_iterator<char>(in), {});
  return run;
}

void WriteHugeLeafMap(const std::string& path) {
  std::string bytes = "# Octomap OcTree binary file\nid OcTree\nsize 12\nres 0.1\ndata\n";
  const unsigned char tree[] = {0x03, 0x00, 0x03, 0x00, 0x03, 0x00, 0xAA, 0xAA};
  bytes.append(reinterpret_cast<const char*>(tree), sizeof(tree));
  std::ofstream(path, std::ios::binary) << bytes;
}

bool WriteEditedUrdf(const std::string& source_urdf, const std::string& from, const std::string& to,
                     const std::string& path) {
  std::string text = ReadText(source_urdf);
  const size_t at = text.find(from);
  if (at == std::string::npos) return false;
  text.replace(at, from.size(), to);
  std::ofstream(path) << text;
  return true;
}

std::vector<UrdfNumberEdit> ExtremeUrdfNumbers() {
  return {
      {"collision origin x = 1e308", "<origin xyz=\"0.12 0 -0.02\"", "<origin xyz=\"1e308 0 -0.02\""},
      {"collision origin z = -1e308", "<origin xyz=\"0.12 0 -0.02\"", "<origin xyz=\"0.12 0 -1e308\""},
      {"hip joint origin x = -1e308", "<origin xyz=\"0.0989949 0.0989949 0\"", "<origin xyz=\"-1e308 0.0989949 0\""},
      {"knee joint origin x = 1e308", "<origin xyz=\"0.1 0 0\"", "<origin xyz=\"1e308 0 0\""},
      {"hip joint rpy yaw = 1e308", "rpy=\"0 0 0.785398\"", "rpy=\"0 0 1e308\""},
      {"joint limit upper = 1e308", "upper=\"0.7\"", "upper=\"1e308\""},
      {"joint limit lower = -1e308", "lower=\"-0.7\"", "lower=\"-1e308\""},
      {"foot sphere radius = 1e308", "<sphere radius=\"0.02\"", "<sphere radius=\"1e308\""},
      {"body mass = 1e308", "<mass value=\"2.0\"", "<mass value=\"1e308\""},
  };
}

void WriteSixteenLegUrdf(const std::string& octopod_urdf, const std::string& path) {
  const std::string text = ReadText(octopod_urdf);
  std::set<std::string> legs;  // left1 .. right4, sorted
  const std::string hip = "_coxa_yaw\"";
  for (size_t at = text.find(hip); at != std::string::npos; at = text.find(hip, at + 1)) {
    const size_t quote = text.rfind('"', at);
    legs.insert(text.substr(quote + 1, at - quote - 1));
  }
  std::string extra;
  for (const std::string& leg : legs) {
    for (const std::string& block : LegBlocks(text, leg)) extra += CopiedBlock(block, leg) + "\n";
  }
  std::string head = text.substr(0, text.rfind("</robot>"));
  const std::string name = "robot name=\"octopod\"";
  if (const size_t at = head.find(name); at != std::string::npos) head.replace(at, name.size(), "robot name=\"sixteen\"");
  std::ofstream(path) << head << extra << "</robot>\n";
}

std::vector<std::string> ScenarioPlanArgs(const std::string& tools_dir, const std::string& source_dir,
                                          const std::string& start, const std::string& goal,
                                          const std::string& time_limit) {
  return {tools_dir + "/mfp-plan", "--scenario", source_dir + "/config/scenarios/littledog_flat.yaml", "--start",
          start, "--goal", goal, "--time-limit", time_limit, "--quiet"};
}

std::vector<FlagCase> ExtremeFlags() {
  return {
      {"0,0,1e16", "0.6,0,0", "5", "--start: YAW = 1e16 is outside"},
      {"1e16,0,0", "0.6,0,0", "5", "--start: X = 1e16 is outside"},
      {"0,0,0,", "0.6,0,0", "5", "--start: expected X,Y,YAW"},
      {"0,0,0", "0.6,0,1e16", "5", "--goal: YAW = 1e16 is outside"},
      {"0,0,0", "0.6,0,0", "nan", "--time-limit"},
      {"0,0,0", "0.6,0,0", "inf", "--time-limit"},
      {"0,0,0", "0.6,0,0", "-1", "--time-limit"},
      {"0,0,0", "-1e308,0,0", "5", "--goal: X = -1e308 is outside"},
  };
}

}  // namespace mfp
