#include "planner/formulation/step_encoder.h"

namespace mfp {

StepExpr& StepExpr::operator+=(const StepExpr& other) {
  lin += other.lin;
  rotations.insert(rotations.end(), other.rotations.begin(), other.rotations.end());
  return *this;
}

StepExpr& StepExpr::operator-=(const StepExpr& other) {
  lin -= other.lin;
  for (RotatedOffset r : other.rotations) {
    r.coefficient = -r.coefficient;
    rotations.push_back(r);
  }
  return *this;
}

StepExpr& StepExpr::operator*=(double scale) {
  lin *= scale;
  for (RotatedOffset& r : rotations) r.coefficient *= scale;
  return *this;
}


}  // namespace mfp
