// model::validate on the stiffness-proportional damping fields of a part (Part::damping_ratio,
// Part::element_damping_ratio): range [0, 0.5], one ratio per element, not on rigid parts; every
// message names the part (and element) and gives the values and the fix.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/errors.h"
#include "solver/model/mesh_generators.h"
#include "solver/model/model.h"

namespace crashlink::model {
namespace {

Model two_hexes() {
  Model m;
  m.materials.push_back({"steel", materials::MaterialKind::Elastic, 7850.0, 210e9, 0.3, {}});
  Part p;
  p.name = "bar";
  p.material = 0;
  generate_box(m, p, {{0.0, 0.0, 0.0}, {0.02, 0.01, 0.01}, {2, 1, 1}});
  m.controls.end_time_s = 1e-3;
  return m;
}

void expect_error(const Model& m, const std::string& a, const std::string& b) {
  try {
    validate(m);
    ADD_FAILURE() << "no error";
  } catch (const ModelError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(a), std::string::npos) << msg;
    EXPECT_NE(msg.find(b), std::string::npos) << msg;
  }
}

TEST(DampingRatioValidation, ValidRatiosPass) {
  Model m = two_hexes();
  EXPECT_FALSE(m.parts[0].damped());
  m.parts[0].damping_ratio = 0.5;
  EXPECT_NO_THROW(validate(m));
  EXPECT_TRUE(m.parts[0].damped());
  m.parts[0].element_damping_ratio = {0.0, 0.05};
  EXPECT_NO_THROW(validate(m));
  EXPECT_EQ(m.parts[0].damping_ratio_of(0), 0.0);
  EXPECT_EQ(m.parts[0].damping_ratio_of(1), 0.05);
}

TEST(DampingRatioValidation, OutOfRangeIsAnErrorWithTheValueAndTheFix) {
  Model m = two_hexes();
  m.parts[0].damping_ratio = 0.7;
  expect_error(m, "part 'bar': damping ratio 0.7 outside [0, 0.5]", "e.g. 0.05");
  m.parts[0].damping_ratio = -0.01;
  expect_error(m, "damping ratio -0.01 outside [0, 0.5]", "0: no damping");
  m.parts[0].damping_ratio = std::numeric_limits<double>::quiet_NaN();
  expect_error(m, "damping ratio nan outside", "e.g. 0.05");
}

TEST(DampingRatioValidation, PerElementRatiosNeedOnePerElementInRange) {
  Model m = two_hexes();
  m.parts[0].element_damping_ratio = {0.05};
  expect_error(m, "part 'bar': 1 per-element damping ratios for 2 elements",
               "give one per element or none");
  m.parts[0].element_damping_ratio = {0.05, 0.6};
  expect_error(m, "part 'bar' element 2: damping ratio 0.6 outside [0, 0.5]", "e.g. 0.05");
}

TEST(DampingRatioValidation, RigidPartIsAnError) {
  Model m = two_hexes();
  m.materials[0].kind = materials::MaterialKind::Rigid;
  m.parts[0].damping_ratio = 0.05;
  expect_error(m, "part 'bar': damping ratio on rigid material 'steel' has no effect", "remove it");
}

}  // namespace
}  // namespace crashlink::model
