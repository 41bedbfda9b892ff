#include "planner/search/internal/lagging_floors.h"

#include <algorithm>
#include <utility>

namespace mfp {
namespace {

// The kept subtree of the highest floor (kept must not be empty).
std::vector<SettledSubtree>::iterator Highest(std::vector<SettledSubtree>* kept) {
  return std::max_element(kept->begin(), kept->end(),
                          [](const SettledSubtree& a, const SettledSubtree& b) { return a.floor < b.floor; });
}

}  // namespace

bool LaggingFloors::Keeps(double floor, double target) const {
  if (capacity_ <= 0 || !(floor < target)) return false;
  if (static_cast<int>(kept_.size()) < capacity_) return true;
  double highest = -kInfinity;
  for (const SettledSubtree& s : kept_) highest = std::max(highest, s.floor);
  return floor < highest;
}

void LaggingFloors::Note(SettledSubtree subtree, double target) {
  if (!Keeps(subtree.floor, target)) {
    NoteFloor(subtree.floor);
    return;
  }
  if (static_cast<int>(kept_.size()) >= capacity_) {
    auto highest = Highest(&kept_);
    NoteFloor(highest->floor);
    *highest = std::move(subtree);
    return;
  }
  kept_.push_back(std::move(subtree));
}

void LaggingFloors::NoteFloor(double floor) { rest_floor_ = std::min(rest_floor_, floor); }

double LaggingFloors::Least() const {
  double least = rest_floor_;
  for (const SettledSubtree& s : kept_) least = std::min(least, s.floor);
  return least;
}

}  // namespace mfp
