#include "tools/region_svg.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mfp {

std::string RegionsSvg(const HeightMap& hm, const std::vector<ConvexRegion>& regions) {
  Eigen::Vector2d lo = hm.origin_world_m;
  Eigen::Vector2d hi = lo + hm.resolution_m * Eigen::Vector2d(hm.cols, hm.rows);
  for (const ConvexRegion& r : regions) {
    for (const auto& v : r.vertices_world_m) {
      lo = lo.cwiseMin(v.head<2>());
      hi = hi.cwiseMax(v.head<2>());
    }
  }
  if (!(hi.x() > lo.x()) || !(hi.y() > lo.y())) hi = lo + Eigen::Vector2d(1, 1);
  // About 1200 px across the larger side.
  const double scale = 1200.0 / std::max(hi.x() - lo.x(), hi.y() - lo.y());
  const double width = (hi.x() - lo.x()) * scale, height = (hi.y() - lo.y()) * scale;
  auto X = [&](double x) { return (x - lo.x()) * scale; };
  auto Y = [&](double y) { return (hi.y() - y) * scale; };  // y up in the world, down in SVG
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << width << " " << height << "\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"#fff8e8\"/>\n";
  float zmin = INFINITY, zmax = -INFINITY;
  for (float h : hm.height_m) {
    if (!std::isnan(h)) {
      zmin = std::min(zmin, h);
      zmax = std::max(zmax, h);
    }
  }
  const double cell = hm.resolution_m * scale;
  for (int r = 0; r < hm.rows; ++r) {
    for (int c = 0; c < hm.cols; ++c) {
      const float h = hm.height_m[static_cast<size_t>(hm.Index(r, c))];
      if (std::isnan(h)) continue;
      const double t = zmax > zmin ? (h - zmin) / (zmax - zmin) : 0.5;
      const int g = static_cast<int>(60 + 170 * t);
      const Eigen::Vector2d corner = hm.origin_world_m + hm.resolution_m * Eigen::Vector2d(c, r + 1);
      svg << "<rect x=\"" << X(corner.x()) << "\" y=\"" << Y(corner.y()) << "\" width=\"" << cell
          << "\" height=\"" << cell << "\" fill=\"rgb(" << g << "," << g << "," << g << ")\"/>\n";
    }
  }
  for (const ConvexRegion& region : regions) {
    svg << "<polygon fill=\"rgba(40,120,255,0.25)\" stroke=\"#1050d0\" stroke-width=\"1.5\" points=\"";
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (const auto& v : region.vertices_world_m) {
      svg << X(v.x()) << "," << Y(v.y()) << " ";
      centroid += v.head<2>();
    }
    centroid /= std::max<size_t>(1, region.vertices_world_m.size());
    svg << "\"/>\n<text x=\"" << X(centroid.x()) << "\" y=\"" << Y(centroid.y())
        << "\" font-size=\"14\" text-anchor=\"middle\" fill=\"#a00000\">" << region.id << "</text>\n";
  }
  svg << "<text x=\"8\" y=\"18\" font-size=\"14\">heights " << zmin << " .. " << zmax
      << " m (dark = low), " << regions.size() << " regions</text>\n</svg>\n";
  return svg.str();
}

}  // namespace mfp

namespace mfp {

std::string RegionsSvg(const std::vector<HeightMap>& levels, const std::vector<ConvexRegion>& regions,
                       const std::vector<int>& region_layer) {
  if (levels.size() <= 1) return RegionsSvg(levels.empty() ? HeightMap() : levels.front(), regions);
  // One nested picture per level, side by side (nested <svg> elements keep their own
  // coordinates).
  std::ostringstream body;
  double x = 0.0, height = 0.0;
  for (size_t level = 0; level < levels.size(); ++level) {
    std::vector<ConvexRegion> on_level;
    for (size_t i = 0; i < regions.size() && i < region_layer.size(); ++i) {
      if (region_layer[i] == static_cast<int>(level)) on_level.push_back(regions[i]);
    }
    std::string panel = RegionsSvg(levels[level], on_level);
    const size_t w0 = panel.find("width=\"") + 7;
    const double w = std::stod(panel.substr(w0));
    const size_t h0 = panel.find("height=\"") + 8;
    height = std::max(height, std::stod(panel.substr(h0)));
    std::ostringstream open;
    open << "<svg x=\"" << x << "\" ";
    panel.replace(0, 5, open.str());
    const std::string tag = "<text x=\"8\" y=\"18\" font-size=\"14\">";
    const size_t label = panel.rfind(tag);
    if (label != std::string::npos) panel.insert(label + tag.size(), "level " + std::to_string(level) + ": ");
    body << panel;
    x += w + 20.0;
  }
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << x << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << x << " " << height << "\">\n" << body.str() << "</svg>\n";
  return svg.str();
}

}  // namespace mfp
