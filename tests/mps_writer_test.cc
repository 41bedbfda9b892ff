// The MPS export read back by a small independent reader: the planner's own solution
// must satisfy every row and bound of the file, its integer columns must be the MIQP's,
// and the file's objective at that solution plus objective_offset must be the objective
// the planner reports.
#include "planner/miqp/mps_writer.h"

#include <gtest/gtest.h>

#include <map>
#include <sstream>

#include "planner/formulation/miqp_formulation.h"
#include "planner/miqp/miqp_builder.h"
#include "planner/qp/internal/ipm_relaxation_solver.h"
#include "planner/search/branch_and_bound.h"
#include "tests/test_robots.h"

namespace mfp {
namespace {

// What the reader takes from a free MPS file.
struct ParsedMps {
  std::map<std::string, char> row_type;  // N, E, L, G
  std::string objective_row;
  std::map<std::string, std::map<std::string, double>> columns;  // column -> row -> value
  std::vector<std::string> column_order;
  std::map<std::string, bool> integer;
  std::map<std::string, double> rhs, range;
  std::map<std::string, double> lower, upper;
  std::vector<std::tuple<std::string, std::string, double>> quad;

  double Objective(const std::map<std::string, double>& x) const {
    double v = 0.0;
    for (const auto& [col, rows] : columns) {
      auto it = rows.find(objective_row);
      if (it != rows.end()) v += it->second * x.at(col);
    }
    for (const auto& [a, b, q] : quad) v += (a == b ? 0.5 : 1.0) * q * x.at(a) * x.at(b);
    return v;
  }

  double MaxViolation(const std::map<std::string, double>& x) const {
    std::map<std::string, double> activity;
    for (const auto& [col, rows] : columns)
      for (const auto& [row, value] : rows) activity[row] += value * x.at(col);
    double worst = 0.0;
    for (const auto& [row, type] : row_type) {
      if (type == 'N') continue;
      const double a = activity[row];
      const double b = rhs.count(row) ? rhs.at(row) : 0.0;
      double lo = -1e300, hi = 1e300;
      if (type == 'E') lo = hi = b;
      if (type == 'L') hi = b;
      if (type == 'G') lo = b;
      if (range.count(row)) {
        const double r = std::abs(range.at(row));
        if (type == 'L') lo = b - r;
        if (type == 'G') hi = b + r;
      }
      worst = std::max({worst, lo - a, a - hi});
    }
    for (const auto& col : column_order) {
      worst = std::max({worst, lower.at(col) - x.at(col), x.at(col) - upper.at(col)});
    }
    return worst;
  }
};

ParsedMps ReadMps(const std::string& text) {
  ParsedMps m;
  std::istringstream in(text);
  std::string line, section;
  bool in_integer = false;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string s; words >> s;) w.push_back(s);
    if (line[0] != ' ') {
      section = w[0];
      continue;
    }
    if (section == "ROWS") {
      m.row_type[w[1]] = w[0][0];
      if (w[0] == "N") m.objective_row = w[1];
    } else if (section == "COLUMNS") {
      if (w.size() == 3 && w[1] == "'MARKER'") {
        in_integer = w[2] == "'INTORG'";
        continue;
      }
      if (!m.columns.count(w[0])) m.column_order.push_back(w[0]);
      m.integer[w[0]] = in_integer;
      for (size_t k = 1; k + 1 < w.size(); k += 2) m.columns[w[0]][w[k]] += std::stod(w[k + 1]);
    } else if (section == "RHS") {
      m.rhs[w[1]] = std::stod(w[2]);
    } else if (section == "RANGES") {
      m.range[w[1]] = std::stod(w[2]);
    } else if (section == "BOUNDS") {
      const std::string& col = w[2];
      if (w[0] == "FR") { m.lower[col] = -1e300; m.upper[col] = 1e300; }
      if (w[0] == "MI") m.lower[col] = -1e300;
      if (w[0] == "PL") m.upper[col] = 1e300;
      if (w[0] == "LO") m.lower[col] = std::stod(w[3]);
      if (w[0] == "UP") m.upper[col] = std::stod(w[3]);
      if (w[0] == "FX") m.lower[col] = m.upper[col] = std::stod(w[3]);
    } else if (section == "QUADOBJ") {
      m.quad.emplace_back(w[0], w[1], std::stod(w[2]));
    }
  }
  return m;
}

std::map<std::string, double> Named(const Miqp& p, const Eigen::VectorXd& x) {
  std::map<std::string, double> named;
  for (int j = 0; j < p.num_variables(); ++j) named[p.var_names[j]] = x(j);
  return named;
}

TEST(MpsWriter, HandMadeRowsBoundsAndQuadratic) {
  // min 0.5 (2 u^2 + 2 u v + 4 v^2) - u + 3 k,  1 <= u + v <= 3,  u - k = 0.5,
  // u free, v in [-2, 5], k binary. Every MPS feature the planner uses appears once.
  MiqpBuilder b;
  const int u = b.AddVariable("u", -kInfinity, kInfinity, false);
  const int v = b.AddVariable("v", -2.0, 5.0, false);
  const int k = b.AddBinary("k");
  b.AddRow("ranged", LinExpr::Var(u) + LinExpr::Var(v), 1.0, 3.0);
  b.AddRow("equal", LinExpr::Var(u) - LinExpr::Var(k), 0.5, 0.5);
  b.AddSquaredCost(LinExpr::Var(u) + LinExpr::Var(v, 0.0), 1.0);  // u^2
  b.AddSquaredCost(LinExpr::Var(u, std::sqrt(0.5)) + LinExpr::Var(v, std::sqrt(0.5)), 1.0);  // (u+v)^2 / 2
  b.AddSquaredCost(LinExpr::Var(v, std::sqrt(1.5)), 1.0);
  b.AddLinearCost(LinExpr::Var(u, -1.0) + LinExpr::Var(k, 3.0) + LinExpr::Constant(7.0));
  const Miqp p = b.Build();
  std::ostringstream out;
  WriteMps(p, "hand", out);
  const std::string text = out.str();
  EXPECT_NE(text.find("RANGES"), std::string::npos);
  EXPECT_NE(text.find(" FR BND u"), std::string::npos);
  EXPECT_NE(text.find("'INTORG'"), std::string::npos);
  const ParsedMps m = ReadMps(text);
  EXPECT_EQ(m.row_type.at("ranged"), 'L');
  EXPECT_NEAR(m.range.at("ranged"), 2.0, 1e-15);
  EXPECT_EQ(m.row_type.at("equal"), 'E');
  EXPECT_TRUE(m.integer.at("k"));
  EXPECT_FALSE(m.integer.at("u"));
  EXPECT_EQ(m.lower.at("k"), 0.0);
  EXPECT_EQ(m.upper.at("k"), 1.0);
  // At (u, v, k) = (1.5, 0.5, 1): quadratic u^2 + (u+v)^2/2 + 1.5 v^2 = 2.25 + 2 + 0.375,
  // linear -1.5 + 3: file objective 6.125; the MIQP adds its constant 7.
  const Eigen::Vector3d x(1.5, 0.5, 1.0);
  EXPECT_NEAR(m.Objective(Named(p, x)), 6.125, 1e-12);
  EXPECT_NEAR(p.Objective(x), 6.125 + 7.0, 1e-12);
  EXPECT_NEAR(m.MaxViolation(Named(p, x)), 0.0, 1e-12);
  const Eigen::Vector3d off(3.5, 0.5, 1.0);  // u + v = 4 > 3 and u - k = 2.5
  EXPECT_NEAR(m.MaxViolation(Named(p, off)), 2.0, 1e-12);
}

TEST(MpsWriter, FootstepMiqpRoundTripsThePlannersSolution) {
  const RobotModel robot = SquareQuadruped(0.12, 0.06);
  FootstepProblem problem;
  problem.robot = &robot;
  problem.regions = {MakeRegionFromPolygon(0, {{-0.3, -0.3, 0}, {0.35, -0.3, 0}, {0.35, 0.3, 0}, {-0.3, 0.3, 0}}, 0.0),
                     MakeRegionFromPolygon(1, {{0.4, -0.3, 0.03}, {1.0, -0.3, 0.03}, {1.0, 0.3, 0.03}, {0.4, 0.3, 0.03}}, 0.0)};
  problem.start_feet_world_m = {{0.1, 0.1, 0}, {0.1, -0.1, 0}, {-0.1, 0.1, 0}, {-0.1, -0.1, 0}};
  problem.goal_x_m = 0.45;
  problem.goal_yaw_rad = 0.3;
  problem.num_new_steps = 8;
  const MiqpFormulation formulation(problem, FormulationOptions());
  const Miqp& p = formulation.miqp();
  const auto solver = MakeInteriorPointRelaxationSolver();
  const BranchAndBoundResult result = SolveBranchAndBound(p, *solver, BranchAndBoundOptions());
  ASSERT_EQ(result.status, SolveStatus::kOptimal);
  std::ostringstream out;
  WriteMps(p, "footsteps", out);
  const ParsedMps m = ReadMps(out.str());
  EXPECT_EQ(static_cast<int>(m.column_order.size()), p.num_variables());
  EXPECT_EQ(static_cast<int>(m.row_type.size()), p.num_rows() + 1);
  int integers = 0;
  for (const auto& [col, is_int] : m.integer) integers += is_int ? 1 : 0;
  EXPECT_EQ(integers, p.num_integer());
  const std::map<std::string, double> x = Named(p, result.x);
  EXPECT_LE(m.MaxViolation(x), 1e-6);
  // objective = MPS objective + objective_offset (the MIQP's constant).
  EXPECT_NEAR(m.Objective(x) + p.constant, result.objective, 1e-6 * (1.0 + std::abs(result.objective)));
  EXPECT_GT(std::abs(p.constant), 1.0);  // the offset is really there and really matters
}

}  // namespace
}  // namespace mfp
