// The Python module `mfp` (pybind11): robots, terrain (height maps from numpy, map
// files), regions and plans. Bad input raises ValueError with mfp-plan's message; a plan
// that does not reach the goal is a result with its status. The GIL is released while
// regions are extracted and while planning.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "base/check.h"
#include "base/solve_status.h"
#include "io/height_map_file.h"
#include "io/robot_loader.h"
#include "python/python_planner.h"
#include "terrain/extraction/region_extractor.h"

namespace py = pybind11;

namespace mfp {
namespace {

struct PyPlan {
  PythonPlanResult result;
};

struct PyTerrain {
  PythonTerrain terrain;
};

// Runs f, turning InputError into ValueError (pybind11 maps std::invalid_argument).
template <typename F>
auto Checked(F f) -> decltype(f()) {
  try {
    return f();
  } catch (const InputError& e) {
    throw std::invalid_argument(e.what());
  }
}

Pose2D PoseFrom(const py::sequence& pose, const char* name) {
  if (pose.size() != 3) {
    throw std::invalid_argument(std::string(name) + ": expected three numbers (x, y, yaw) in m, m, rad");
  }
  Pose2D p{pose[0].cast<double>(), pose[1].cast<double>(), pose[2].cast<double>()};
  if (!std::isfinite(p.x_m) || !std::isfinite(p.y_m) || !std::isfinite(p.yaw_rad)) {
    throw std::invalid_argument(std::string(name) + ": expected three finite numbers X,Y,YAW (m, m, rad)");
  }
  return p;
}

// The numpy array (any float dtype, any strides) as a grid: heights[i, j] at
// origin + (i, j) * resolution.
PyTerrain TerrainFromHeights(const py::array& heights, double resolution, const py::sequence& origin,
                             py::object unknown, py::object variance, py::object max_variance) {
  if (heights.ndim() != 2) {
    throw std::invalid_argument("height map: heights must be a 2-D array (heights[i, j], i along x), got " +
                                std::to_string(heights.ndim()) + " dimensions");
  }
  if (origin.size() != 2) throw std::invalid_argument("height map origin: expected (x, y) of the centre of cell (0, 0) [m]");
  const auto h = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(heights);
  if (!h) throw std::invalid_argument("height map: heights must be numbers");
  NpyArray array;
  array.rows = static_cast<size_t>(h.shape(0));
  array.cols = static_cast<size_t>(h.shape(1));
  if (array.rows * array.cols > kDefaultMaxHeightMapCells) {
    throw std::invalid_argument("height map has " + std::to_string(array.rows) + " x " + std::to_string(array.cols) +
                                " cells, more than the limit of " + std::to_string(kDefaultMaxHeightMapCells));
  }
  array.values.assign(h.data(), h.data() + h.size());
  const double unknown_value = unknown.is_none() ? std::numeric_limits<double>::quiet_NaN() : unknown.cast<double>();
  PyTerrain out;
  out.terrain.source = "height map";
  out.terrain.grid = Checked([&] {
    return HeightGridFromArray(array, resolution, origin[0].cast<double>(), origin[1].cast<double>(), unknown_value);
  });
  if (!variance.is_none()) {
    const auto v = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(variance);
    if (!v || v.ndim() != 2 || static_cast<size_t>(v.shape(0)) != array.rows ||
        static_cast<size_t>(v.shape(1)) != array.cols) {
      throw std::invalid_argument("height map variance: give an array of the heights' shape [m^2]");
    }
    out.terrain.grid->variances_m2.assign(v.data(), v.data() + v.size());
    out.terrain.grid->max_variance_m2 =
        max_variance.is_none() ? 0.25 * resolution * resolution : max_variance.cast<double>();
    Checked([&] { ValidateHeightGrid(*out.terrain.grid); });
  }
  return out;
}

PythonPlanInputs InputsFrom(const py::sequence& start, const py::sequence& goal, double time_limit,
                            const py::dict& options) {
  PythonPlanInputs in;
  in.start = PoseFrom(start, "start");
  in.goal = PoseFrom(goal, "goal");
  if (!(time_limit >= 0.0 && time_limit <= 3600.0)) {
    throw std::invalid_argument("time_limit: " + std::to_string(time_limit) + " s is outside [0.001, 3600] s (0: default)");
  }
  in.time_limit_s = time_limit;
  for (const auto& item : options) {
    const std::string key = item.first.cast<std::string>();
    const py::handle value = item.second;
    auto int_in = [&](int lo, int hi) {
      const int v = value.cast<int>();
      if (v < lo || v > hi) {
        throw std::invalid_argument("options['" + key + "'] = " + std::to_string(v) + " is outside [" +
                                    std::to_string(lo) + ", " + std::to_string(hi) + "]");
      }
      return v;
    };
    if (key == "window") {
      in.window = int_in(1, 1000);
    } else if (key == "max_steps") {
      in.max_steps = int_in(1, 100000);
    } else if (key == "threads") {
      in.threads = int_in(1, 64);
    } else if (key == "polish") {
      in.polish = value.cast<bool>();
    } else if (key == "relaxation_solver") {
      in.relaxation_solver = value.cast<std::string>();
    } else {
      throw std::invalid_argument("options: unknown key '" + key +
                                  "' (known: window, max_steps, threads, polish, relaxation_solver)");
    }
  }
  return in;
}

py::array_t<double> FootstepRows(const Plan& plan) {
  py::array_t<double> rows({static_cast<py::ssize_t>(plan.footsteps.size()), py::ssize_t{5}});
  auto r = rows.mutable_unchecked<2>();
  for (size_t i = 0; i < plan.footsteps.size(); ++i) {
    const Footstep& f = plan.footsteps[i];
    const py::ssize_t k = static_cast<py::ssize_t>(i);
    r(k, 0) = f.leg;
    r(k, 1) = f.position_world_m.x();
    r(k, 2) = f.position_world_m.y();
    r(k, 3) = f.position_world_m.z();
    r(k, 4) = f.yaw_rad;
  }
  return rows;
}

py::list RegionList(const std::vector<ConvexRegion>& regions) {
  py::list out;
  for (const ConvexRegion& r : regions) {
    py::array_t<double> vertices({static_cast<py::ssize_t>(r.vertices_world_m.size()), py::ssize_t{3}});
    auto v = vertices.mutable_unchecked<2>();
    for (size_t i = 0; i < r.vertices_world_m.size(); ++i) {
      for (int d = 0; d < 3; ++d) v(static_cast<py::ssize_t>(i), d) = r.vertices_world_m[i][d];
    }
    py::array_t<double> A({static_cast<py::ssize_t>(r.A.rows()), py::ssize_t{3}});
    auto a = A.mutable_unchecked<2>();
    for (Eigen::Index i = 0; i < r.A.rows(); ++i) {
      for (int d = 0; d < 3; ++d) a(i, d) = r.A(i, d);
    }
    py::array_t<double> b(static_cast<py::ssize_t>(r.b.size()));
    for (Eigen::Index i = 0; i < r.b.size(); ++i) b.mutable_at(i) = r.b(i);
    py::dict d;
    d["id"] = r.id;
    d["vertices"] = vertices;
    d["normal"] = py::make_tuple(r.normal_world.x(), r.normal_world.y(), r.normal_world.z());
    d["A"] = A;
    d["b"] = b;
    d["area"] = r.area_m2;
    out.append(d);
  }
  return out;
}

// Regions with mfp-regions' defaults, or the options a robot plans with.
py::list TerrainRegionList(const PyTerrain& t, const RobotModel* robot) {
  RegionExtractorOptions options;
  if (robot != nullptr) options = ScenarioRegionOptions(Scenario(), *robot);
  std::vector<ConvexRegion> regions;
  {
    py::gil_scoped_release release;
    regions = Checked([&] { return TerrainRegions(t.terrain, options); });
  }
  return RegionList(regions);
}

PyPlan PlanFromPython(const RobotModel& robot, const PyTerrain& terrain, const py::sequence& start, const py::sequence& goal,
            double time_limit, const py::object& options) {
  const py::dict opts = options.is_none() ? py::dict() : options.cast<py::dict>();
  const PythonPlanInputs inputs = InputsFrom(start, goal, time_limit, opts);
  py::gil_scoped_release release;
  return PyPlan{Checked([&] { return PlanOnTerrain(robot, terrain.terrain, inputs); })};
}

}  // namespace
}  // namespace mfp

PYBIND11_MODULE(mfp, m) {
  using namespace mfp;
  m.doc() = "mfp: footstep planning for multilegged robots (mixed-integer convex optimisation)";
  py::class_<RobotModel>(m, "Robot")
      .def_property_readonly("name", [](const RobotModel& r) { return r.name; })
      .def_property_readonly("num_legs", &RobotModel::num_legs)
      .def_property_readonly("leg_names", [](const RobotModel& r) {
        std::vector<std::string> names;
        for (const auto& leg : r.legs) names.push_back(leg.name);
        return names;
      })
      .def_property_readonly("foot_radius", [](const RobotModel& r) { return r.foot_radius_m; })
      .def_property_readonly("stance_height", [](const RobotModel& r) { return r.stance_height_m; });
  m.def("load_robot", [](const std::string& path) { return Checked([&] { return LoadRobot(path); }); },
        py::arg("path"), "A robot from a URDF alone or a robot YAML (config/robots/NAME.yaml).");

  py::class_<PyTerrain>(m, "Terrain")
      .def_static("from_height_map", &TerrainFromHeights, py::arg("heights"), py::arg("resolution"),
                  py::arg("origin") = py::make_tuple(0.0, 0.0), py::arg("unknown") = py::none(),
                  py::arg("variance") = py::none(), py::arg("max_variance") = py::none(),
                  "heights[i, j]: surface height [m] of the cell centred at origin + (i, j) * resolution; NaN = unknown.")
      .def_static("from_octomap", [](const std::string& path) {
        if (IsHeightMapPath(path)) throw std::invalid_argument(path + ": not an OctoMap (.bt or .ot); use Terrain.from_file");
        return PyTerrain{Checked([&] { return TerrainFromFile(path); })};
      }, py::arg("path"))
      .def_static("from_file", [](const std::string& path) { return PyTerrain{Checked([&] { return TerrainFromFile(path); })}; },
                  py::arg("path"), "An OctoMap (.bt, .ot) or a height map (.npy with its .yaml, or the .yaml).")
      .def_property_readonly("regions", [](const PyTerrain& t) { return TerrainRegionList(t, nullptr); },
                             "Regions with mfp-regions' default options (id, vertices, normal, A, b, area).")
      .def("regions_for", [](const PyTerrain& t, const RobotModel& robot) { return TerrainRegionList(t, &robot); },
           py::arg("robot"), "The regions mfp.plan uses for this robot.");

  py::class_<PyPlan>(m, "Plan")
      .def_property_readonly("status", [](const PyPlan& p) { return std::string(ToString(p.result.plan.status)); })
      .def_property_readonly("reaches_goal", [](const PyPlan& p) { return p.result.plan.reaches_goal; })
      .def_property_readonly("message", [](const PyPlan& p) { return p.result.plan.message; })
      .def_property_readonly("objective", [](const PyPlan& p) { return p.result.plan.objective; })
      .def_property_readonly("solve_time", [](const PyPlan& p) { return p.result.plan.solve_time_s; })
      .def_property_readonly("footsteps", [](const PyPlan& p) { return FootstepRows(p.result.plan); },
                             "One row per footstep: leg, x, y, z, yaw (the first rows are the start stance).")
      .def_property_readonly("regions", [](const PyPlan& p) { return RegionList(p.result.regions); })
      .def("to_json", [](const PyPlan& p) { return p.result.json; }, "The JSON mfp-plan --json writes.")
      .def("__repr__", [](const PyPlan& p) {
        return "<mfp.Plan " + std::string(ToString(p.result.plan.status)) +
               (p.result.plan.reaches_goal ? ", reaches goal, " : ", does not reach goal, ") +
               std::to_string(p.result.plan.footsteps.size()) + " footsteps>";
      });

  m.def("plan", &PlanFromPython, py::arg("robot"), py::arg("terrain"), py::arg("start"), py::arg("goal"),
        py::arg("time_limit") = 0.0, py::arg("options") = py::none(),
        "Plans footsteps from start to goal (x, y, yaw) as mfp-plan does; time_limit in s (0: default).");
}
