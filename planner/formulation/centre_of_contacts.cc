#include "planner/formulation/centre_of_contacts.h"

#include <string>

namespace mfp {

void AddFootstepPositions(const Box3& box, int num_steps, int n, MiqpBuilder* b, FootstepVariables* vars) {
  vars->x.assign(num_steps, -1);
  vars->y.assign(num_steps, -1);
  vars->z.assign(num_steps, -1);
  for (int i = n; i < num_steps; ++i) {
    vars->x[i] = b->AddVariable(StepName("x", i), box.lo.x(), box.hi.x(), false);
    vars->y[i] = b->AddVariable(StepName("y", i), box.lo.y(), box.hi.y(), false);
    vars->z[i] = b->AddVariable(StepName("z", i), box.lo.z(), box.hi.z(), false);
  }
}

void AddCentreOfContacts(const StepExpressions& e, const Box3& box, int num_steps, MiqpBuilder* b,
                         FootstepVariables* vars) {
  vars->px.assign(num_steps, -1);
  vars->py.assign(num_steps, -1);
  for (int i = e.num_legs(); i < num_steps; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      const std::string name = std::string(axis == 0 ? "px_" : "py_") + std::to_string(i);
      const int p = b->AddVariable(name, box.lo(axis), box.hi(axis), false);
      (axis == 0 ? vars->px : vars->py)[i] = p;
      b->AddRow("def_" + name, e.CentreOfContactsSum(i, axis) - LinExpr::Var(p), 0.0, 0.0);
    }
  }
}

}  // namespace mfp
