// The frame finite-element model (src/stiffness/frame_model.hpp, frame_structure.hpp) against what it must
// equal, on random geometries with fixed seeds:
//  - a rigid frame (every strut's node fixed, or no frame) with bar-only struts is the strut-only model
//    K = Gᵀ diag(k) G to 1e-9: random hexapods at random poses, the tripod (reduced DOF: the platform master
//    restricted to the allowed twists), a glide machine with compliant joints, drives and guides in series;
//  - every base joint on one column: the tool's compliance is the struts' plus the column's closed-form
//    cantilever carried rigidly to the tool point, C = C_s + R Γᵀ C_cantilever Γ Rᵀ;
//  - splitting every beam into 10 elements leaves the nodal displacements unchanged (frame alone under random
//    nodal loads, and the whole machine under a tool load);
//  - C symmetric positive definite, and an elastic frame only adds compliance (C_frame − C_rigid ⪰ 0);
//  - a hexapod is statically determinate: the struts' forces are statics' whatever the frame;
//  - the deflection is linear in the load, reciprocal (Maxwell–Betti), and C w;
//  - a frame that is a mechanism is refused as a singular stiffness matrix, with the file and line.
#include "stiffness/frame_model.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <random>

#include "core/rotation.hpp"
#include "dynamics/dynamics_test_support.hpp"
#include "machine/limits_test_support.hpp"
#include "statics/actuator_forces.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

using stiffness::FrameModel;
using stiffness::Matrix6;
using FrameVector6 = Eigen::Matrix<double, 6, 1>;

// Steel sections of a machine frame: radii of gyration 40…120 mm, torsion near the polar moment.
BeamSection random_frame_section(std::mt19937_64& rng) {
  BeamSection s;
  s.modulus_N_mm2 = test::uniform(rng, 2.0e5, 2.1e5);
  s.shear_modulus_N_mm2 = s.modulus_N_mm2 / 2.6;
  s.area_mm2 = test::uniform(rng, 2e3, 1.2e4);
  const double rx = test::uniform(rng, 40, 120), ry = test::uniform(rng, 40, 120);
  s.second_moment_x_mm4 = s.area_mm2 * rx * rx;
  s.second_moment_y_mm4 = s.area_mm2 * ry * ry;
  s.torsion_constant_mm4 = test::uniform(rng, 0.5, 1.0) * (s.second_moment_x_mm4 + s.second_moment_y_mm4);
  return s;
}

Eigen::Vector3d random_frame_direction(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
}

void add_frame_node(FrameParameters& frame, const std::string& name, const Eigen::Vector3d& at, bool fixed) {
  frame.nodes.push_back({name, at, fixed, 0});
}

void add_frame_beam(FrameParameters& frame, int from, int to, const BeamSection& section,
                    const Eigen::Vector3d& section_x) {
  FrameBeam beam;
  beam.from = from;
  beam.to = to;
  beam.section = section;
  beam.section_x = section_x;
  frame.beams.push_back(beam);
}

// A frame round a machine's base joints: under every joint a column from a fixed foot 400…700 mm below to a
// top node near the joint (the joint rigidly offset from it), the tops joined in a ring, with random steel
// sections and section orientations.
FrameParameters column_frame(std::mt19937_64& rng, const StrutJointPoints& ends, int struts) {
  FrameParameters frame;
  for (int j = 0; j < struts; ++j) {
    const Eigen::Vector3d top =
        ends.base_mm[j] + Eigen::Vector3d(test::uniform(rng, -30, 30), test::uniform(rng, -30, 30), -40.0);
    add_frame_node(frame, fmt::format("foot{}", j), top - Eigen::Vector3d(0, 0, test::uniform(rng, 400, 700)),
                   true);
    add_frame_node(frame, fmt::format("top{}", j), top, false);
    frame.strut_nodes.push_back(2 * j + 1);
  }
  for (int j = 0; j < struts; ++j) {
    add_frame_beam(frame, 2 * j, 2 * j + 1, random_frame_section(rng), Eigen::Vector3d(1, 0, 0));
    add_frame_beam(frame, 2 * j + 1, 2 * ((j + 1) % struts) + 1, random_frame_section(rng),
                   Eigen::Vector3d(0, 0, 1) + 0.3 * random_frame_direction(rng));
  }
  frame.source = "generated";
  return frame;
}

// The same frame with every beam cut into `parts` equal elements (new nodes appended: the old keep their
// indices), each with the beam's section and orientation.
FrameParameters split_frame(const FrameParameters& frame, int parts) {
  FrameParameters out = frame;
  out.beams.clear();
  for (const FrameBeam& beam : frame.beams) {
    const Eigen::Vector3d a = frame.nodes[beam.from].position_mm, b = frame.nodes[beam.to].position_mm;
    int previous = beam.from;
    for (int k = 1; k <= parts; ++k) {
      int next = beam.to;
      if (k < parts) {
        next = static_cast<int>(out.nodes.size());
        add_frame_node(out, fmt::format("split{}", next), a + (b - a) * (static_cast<double>(k) / parts),
                       false);
      }
      add_frame_beam(out, previous, next, beam.section, beam.section_x);
      previous = next;
    }
  }
  return out;
}

StiffnessParameters random_frame_struts(std::mt19937_64& rng, int struts) {
  StiffnessParameters p;
  p.strut_count = struts;
  p.line = 1;
  for (int j = 0; j < struts; ++j) p.struts[j].stiffness_N_mm = test::uniform(rng, 5e4, 4e5);
  return p;
}

Pose random_frame_pose(std::mt19937_64& rng, const Pose& home) {
  Pose p = home;
  p.position_mm +=
      Eigen::Vector3d(test::uniform(rng, -40, 40), test::uniform(rng, -40, 40), test::uniform(rng, -40, 40));
  p.rotation = rotation_from_rotation_vector(0.1 * random_frame_direction(rng)) * p.rotation;
  return p;
}

// ‖a − b‖ / ‖b‖ with rotations scaled by `size_mm`, so that mm and rad entries weigh alike.
double frame_compliance_difference(const Matrix6& a, const Matrix6& b, double size_mm) {
  FrameVector6 scale;
  scale << 1, 1, 1, size_mm, size_mm, size_mm;
  return (scale.asDiagonal() * (a - b) * scale.asDiagonal()).norm() /
         (scale.asDiagonal() * b * scale.asDiagonal()).norm();
}

statics::Wrench random_frame_wrench(std::mt19937_64& rng) {
  return {Eigen::Vector3d(test::uniform(rng, -500, 500), test::uniform(rng, -500, 500),
                          test::uniform(rng, -500, 500)),
          Eigen::Vector3d(test::uniform(rng, -5e4, 5e4), test::uniform(rng, -5e4, 5e4),
                          test::uniform(rng, -5e4, 5e4))};
}

FrameVector6 frame_wrench_vector(const statics::Wrench& w) {
  FrameVector6 v;
  v << w.force_N, w.moment_Nmm;
  return v;
}

TEST(FrameModel, RigidFrameWithBarStrutsIsTheStrutOnlyModel) {
  std::mt19937_64 rng(1510);
  for (int i = 0; i < 5; ++i) {
    const Machine machine = test::random_hexapod_machine(rng, i);
    const Mechanism& mech = *machine.mechanism;
    StiffnessParameters parameters = random_frame_struts(rng, 6);
    // Every strut on a fixed node offset from its joint (the offset must not matter), or no frame at all.
    StrutJointPoints ends;
    ASSERT_EQ(mech.strut_ends(mech.home(), ends), 6);
    StiffnessParameters fixed_frame = parameters;
    for (int j = 0; j < 6; ++j) {
      add_frame_node(fixed_frame.frame, fmt::format("n{}", j),
                     ends.base_mm[j] + 100 * random_frame_direction(rng), true);
      fixed_frame.frame.strut_nodes.push_back(j);
    }
    for (const StiffnessParameters* p : {&parameters, &fixed_frame}) {
      auto model = FrameModel::make(mech, *p);
      ASSERT_TRUE(model.ok()) << model.error().message;
      EXPECT_EQ(model->unknowns(), 6);
      for (int trial = 0; trial < 4; ++trial) {
        const Pose pose = random_frame_pose(rng, mech.home());
        auto fe = model->compliance(pose);
        auto bars = stiffness::strut_compliance(mech, *p, pose);
        ASSERT_TRUE(fe.ok() && bars.ok());
        EXPECT_LT(frame_compliance_difference(fe->compliance, bars->compliance, mech.platform_size_mm()),
                  1e-9);
        EXPECT_EQ(fe->dof, 6);
        EXPECT_LT((fe->strut_stiffness_N_mm - bars->strut_stiffness_N_mm).cwiseAbs().maxCoeff(), 1e-6);
      }
    }
  }
}

TEST(FrameModel, RigidFrameMatchesTheStrutOnlyModelOfReducedAndGlideMachines) {
  std::mt19937_64 rng(1511);
  for (const char* file : {"tripod.yaml", "hexaglide.yaml", "triglide.yaml", "rotopod.yaml"}) {
    SCOPED_TRACE(file);
    const Machine machine = test::machine_from_example(std::string("examples/machines/") + file);
    const Mechanism& mech = *machine.mechanism;
    StiffnessParameters p = random_frame_struts(rng, mech.actuator_count());
    // The joints, and where there are carriages their drives and guides, in series with the struts.
    p.model = StiffnessModel::struts_joints;
    for (int j = 0; j < p.strut_count; ++j) {
      p.joints[j].base_mm_N = test::uniform(rng, 0, 2e-6);
      p.joints[j].platform_mm_N = test::uniform(rng, 0, 2e-6);
      p.carriages[j].drive_stiffness_N_mm = test::uniform(rng, 5e4, 2e5);
      p.carriages[j].guide_mm_N = test::uniform(rng, 0, 5e-6);
    }
    auto model = FrameModel::make(mech, p);
    ASSERT_TRUE(model.ok()) << model.error().message;
    const Pose home = *mech.complete_pose(mech.home());
    auto fe = model->compliance(home);
    auto bars = stiffness::strut_compliance(mech, p, home);
    ASSERT_TRUE(fe.ok()) << fe.error().message;
    ASSERT_TRUE(bars.ok()) << bars.error().message;
    EXPECT_EQ(fe->dof, bars->dof);
    EXPECT_LT(frame_compliance_difference(fe->compliance, bars->compliance, mech.platform_size_mm()), 1e-9);
  }
}

TEST(FrameModel, StrutsOnOneColumnAddTheCantileverCarriedToTheTool) {
  std::mt19937_64 rng(1512);
  for (int i = 0; i < 4; ++i) {
    const Machine machine = test::random_hexapod_machine(rng, 10 + i);
    const Mechanism& mech = *machine.mechanism;
    StiffnessParameters p = random_frame_struts(rng, 6);
    // A column from a fixed foot to a node that carries every base joint, in any direction.
    const Eigen::Vector3d top(test::uniform(rng, -100, 100), test::uniform(rng, -100, 100), -200);
    const Eigen::Vector3d foot = top - test::uniform(rng, 300, 900) * random_frame_direction(rng);
    const BeamSection section = random_frame_section(rng);
    const Eigen::Vector3d section_x = random_frame_direction(rng);
    add_frame_node(p.frame, "foot", foot, true);
    add_frame_node(p.frame, "top", top, false);
    add_frame_beam(p.frame, 0, 1, section, section_x);
    p.frame.strut_nodes.assign(6, 1);
    auto model = FrameModel::make(mech, p);
    ASSERT_TRUE(model.ok()) << model.error().message;
    const Pose pose = random_frame_pose(rng, mech.home());
    auto fe = model->compliance(pose);
    auto bars = stiffness::strut_compliance(mech, p, pose);
    ASSERT_TRUE(fe.ok() && bars.ok());
    // The column's tip compliance in the base frame, carried to the tool point as a rigid body.
    const Eigen::Matrix3d gamma = stiffness::beam_axes(top - foot, section_x);
    Matrix6 big_gamma = Matrix6::Zero();
    big_gamma.block<3, 3>(0, 0) = big_gamma.block<3, 3>(3, 3) = gamma;
    const Matrix6 column =
        big_gamma.transpose() * stiffness::cantilever_compliance(section, (top - foot).norm()) * big_gamma;
    const Matrix6 carry = stiffness::rigid_transfer(fe->pose.position_mm - top);
    const Matrix6 expected = bars->compliance + carry * column * carry.transpose();
    EXPECT_LT(frame_compliance_difference(fe->compliance, expected, mech.platform_size_mm()), 1e-9);
  }
}

TEST(FrameModel, SplittingEveryBeamIntoTenLeavesTheFramesDisplacementsUnchanged) {
  std::mt19937_64 rng(1513);
  for (int trial = 0; trial < 5; ++trial) {
    // A random frame: nodes in a 2 m box, each joined to an earlier one (a tree from the fixed first nodes)
    // and a few more beams making loops.
    FrameParameters frame;
    const int count = 8 + trial * 3;
    for (int n = 0; n < count; ++n) {
      add_frame_node(frame, fmt::format("n{}", n),
                     Eigen::Vector3d(test::uniform(rng, 0, 2000), test::uniform(rng, 0, 2000),
                                     test::uniform(rng, 0, 2000)),
                     n < 2);
    }
    for (int n = 1; n < count; ++n) {
      add_frame_beam(frame, static_cast<int>(test::uniform(rng, 0, n - 1e-9)), n, random_frame_section(rng),
                     random_frame_direction(rng));
    }
    for (int extra = 0; extra < count / 2; ++extra) {
      const int a = static_cast<int>(test::uniform(rng, 0, count - 1e-9));
      const int b = (a + 1 + static_cast<int>(test::uniform(rng, 0, count - 1 - 1e-9))) % count;
      add_frame_beam(frame, a, b, random_frame_section(rng), random_frame_direction(rng));
    }
    std::vector<stiffness::Vector6> loads(count);
    for (auto& load : loads) {
      load << test::uniform(rng, -1e3, 1e3), test::uniform(rng, -1e3, 1e3), test::uniform(rng, -1e3, 1e3),
          test::uniform(rng, -1e5, 1e5), test::uniform(rng, -1e5, 1e5), test::uniform(rng, -1e5, 1e5);
    }
    auto whole = stiffness::frame_displacements(frame, loads);
    ASSERT_TRUE(whole.ok()) << whole.error().message;
    const FrameParameters split = split_frame(frame, 10);
    ASSERT_EQ(split.beams.size(), 10 * frame.beams.size());
    std::vector<stiffness::Vector6> split_loads = loads;
    split_loads.resize(split.nodes.size(), stiffness::Vector6::Zero());
    auto parts = stiffness::frame_displacements(split, split_loads);
    ASSERT_TRUE(parts.ok()) << parts.error().message;
    double largest = 0.0, worst = 0.0;
    for (int n = 0; n < count; ++n) {
      FrameVector6 scaled = (*whole)[n], difference = (*parts)[n] - (*whole)[n];
      scaled.tail<3>() *= 1000.0;  // rotations at a 1 m lever
      difference.tail<3>() *= 1000.0;
      largest = std::max(largest, scaled.cwiseAbs().maxCoeff());
      worst = std::max(worst, difference.cwiseAbs().maxCoeff());
    }
    EXPECT_GT(largest, 0.0);
    EXPECT_LT(worst, 1e-9 * largest) << "trial " << trial;
  }
}

TEST(FrameModel, SplittingEveryBeamIntoTenLeavesTheMachinesDeflectionUnchanged) {
  std::mt19937_64 rng(1514);
  for (int i = 0; i < 3; ++i) {
    const Machine machine = test::random_hexapod_machine(rng, 20 + i);
    const Mechanism& mech = *machine.mechanism;
    StrutJointPoints ends;
    ASSERT_EQ(mech.strut_ends(mech.home(), ends), 6);
    StiffnessParameters p = random_frame_struts(rng, 6);
    p.frame = column_frame(rng, ends, 6);
    StiffnessParameters split = p;
    split.frame = split_frame(p.frame, 10);
    auto coarse = FrameModel::make(mech, p);
    auto fine = FrameModel::make(mech, split);
    ASSERT_TRUE(coarse.ok() && fine.ok());
    const Pose pose = random_frame_pose(rng, mech.home());
    const statics::Wrench load = random_frame_wrench(rng);
    stiffness::FrameDeflection a = coarse->make_deflection(), b = fine->make_deflection();
    ASSERT_TRUE(coarse->deflection(pose, load, a).ok());
    ASSERT_TRUE(fine->deflection(pose, load, b).ok());
    const double size = mech.platform_size_mm();
    FrameVector6 scale;
    scale << 1, 1, 1, size, size, size;
    EXPECT_LT((scale.asDiagonal() * (b.tool - a.tool)).norm(), 1e-9 * (scale.asDiagonal() * a.tool).norm());
    for (std::size_t n = 0; n < p.frame.nodes.size(); ++n) {
      EXPECT_LT((scale.asDiagonal() * (b.node_displacement[n] - a.node_displacement[n])).norm(),
                1e-9 * (scale.asDiagonal() * a.tool).norm())
          << "node " << n;
    }
    EXPECT_LT((b.strut_tension_N - a.strut_tension_N).cwiseAbs().maxCoeff(),
              1e-9 * a.strut_tension_N.cwiseAbs().maxCoeff());
  }
}

TEST(FrameModel, ComplianceIsSymmetricPositiveDefiniteAndAFrameOnlyAddsToIt) {
  std::mt19937_64 rng(1515);
  for (int i = 0; i < 5; ++i) {
    const Machine machine = test::random_hexapod_machine(rng, 30 + i);
    const Mechanism& mech = *machine.mechanism;
    StrutJointPoints ends;
    ASSERT_EQ(mech.strut_ends(mech.home(), ends), 6);
    StiffnessParameters p = random_frame_struts(rng, 6);
    p.frame = column_frame(rng, ends, 6);
    auto model = FrameModel::make(mech, p);
    ASSERT_TRUE(model.ok()) << model.error().message;
    EXPECT_EQ(model->unknowns(), 6 * 6 + 6);
    const Pose pose = random_frame_pose(rng, mech.home());
    auto fe = model->compliance(pose);
    auto rigid = stiffness::strut_compliance(mech, p, pose);
    ASSERT_TRUE(fe.ok() && rigid.ok());
    const Matrix6& c = fe->compliance;
    EXPECT_LE((c - c.transpose()).cwiseAbs().maxCoeff(), 1e-15 * c.cwiseAbs().maxCoeff());
    FrameVector6 scale;
    scale << 1, 1, 1, mech.platform_size_mm(), mech.platform_size_mm(), mech.platform_size_mm();
    const Matrix6 scaled = scale.asDiagonal() * c * scale.asDiagonal();
    EXPECT_EQ(Eigen::LLT<Matrix6>(scaled).info(), Eigen::Success);
    const Eigen::SelfAdjointEigenSolver<Matrix6> added(scale.asDiagonal() * (c - rigid->compliance) *
                                                       scale.asDiagonal());
    EXPECT_GT(added.eigenvalues().minCoeff(), -1e-9 * added.eigenvalues().maxCoeff());
    EXPECT_GT(added.eigenvalues().maxCoeff(),
              1e-6 * Eigen::SelfAdjointEigenSolver<Matrix6>(scaled).eigenvalues().maxCoeff());
  }
}

TEST(FrameModel, HexapodStrutForcesAreStaticsWhateverTheFrame) {
  std::mt19937_64 rng(1516);
  for (int i = 0; i < 4; ++i) {
    const Machine machine = test::random_hexapod_machine(rng, 40 + i);
    const Mechanism& mech = *machine.mechanism;
    StrutJointPoints ends;
    ASSERT_EQ(mech.strut_ends(mech.home(), ends), 6);
    StiffnessParameters p = random_frame_struts(rng, 6);
    p.frame = column_frame(rng, ends, 6);
    auto model = FrameModel::make(mech, p);
    ASSERT_TRUE(model.ok());
    stiffness::FrameDeflection d = model->make_deflection();
    const Pose pose = random_frame_pose(rng, mech.home());
    const statics::Wrench load = random_frame_wrench(rng);
    ASSERT_TRUE(model->deflection(pose, load, d).ok());
    auto forces = statics::actuator_forces(mech, pose, load);
    ASSERT_TRUE(forces.ok()) << forces.error().message;
    // Statics' P pushes the platform: a compression, the negative of the tension.
    EXPECT_LT((d.strut_tension_N + *forces).cwiseAbs().maxCoeff(), 1e-8 * forces->cwiseAbs().maxCoeff());
  }
}

TEST(FrameModel, DeflectionIsLinearReciprocalAndTheComplianceTimesTheLoad) {
  std::mt19937_64 rng(1517);
  const Machine machine = test::random_hexapod_machine(rng, 50);
  const Mechanism& mech = *machine.mechanism;
  StrutJointPoints ends;
  ASSERT_EQ(mech.strut_ends(mech.home(), ends), 6);
  StiffnessParameters p = random_frame_struts(rng, 6);
  p.frame = column_frame(rng, ends, 6);
  auto model = FrameModel::make(mech, p);
  ASSERT_TRUE(model.ok());
  stiffness::FrameDeflection d1 = model->make_deflection(), d2 = model->make_deflection(),
                             sum = model->make_deflection();
  for (int trial = 0; trial < 5; ++trial) {
    const Pose pose = random_frame_pose(rng, mech.home());
    const statics::Wrench w1 = random_frame_wrench(rng), w2 = random_frame_wrench(rng);
    const double factor = test::uniform(rng, -3, 3);
    const statics::Wrench combined{factor * w1.force_N + w2.force_N, factor * w1.moment_Nmm + w2.moment_Nmm};
    ASSERT_TRUE(model->deflection(pose, w1, d1).ok());
    ASSERT_TRUE(model->deflection(pose, w2, d2).ok());
    ASSERT_TRUE(model->deflection(pose, combined, sum).ok());
    const FrameVector6 linear = factor * d1.tool + d2.tool;
    EXPECT_LT((sum.tool - linear).norm(), 1e-10 * linear.norm());
    for (std::size_t n = 0; n < p.frame.nodes.size(); ++n) {
      const FrameVector6 expected = factor * d1.node_displacement[n] + d2.node_displacement[n];
      EXPECT_LT((sum.node_displacement[n] - expected).norm(), 1e-10 * linear.norm());
    }
    // Maxwell–Betti: the work of one load on the other's deflection.
    const double w1_on_2 = frame_wrench_vector(w1).dot(d2.tool),
                 w2_on_1 = frame_wrench_vector(w2).dot(d1.tool);
    EXPECT_NEAR(w1_on_2, w2_on_1, 1e-10 * (std::abs(w1_on_2) + std::abs(w2_on_1)));
    auto c = model->compliance(pose);
    ASSERT_TRUE(c.ok());
    const FrameVector6 cw = c->compliance * frame_wrench_vector(w1);
    EXPECT_LT((cw - d1.tool).norm(), 1e-10 * cw.norm());
    // Doubling every modulus (struts and beams) halves the deflection.
    if (trial == 0) {
      StiffnessParameters stiffer = p;
      for (int j = 0; j < 6; ++j) stiffer.struts[j].stiffness_N_mm *= 2;
      for (FrameBeam& beam : stiffer.frame.beams) {
        beam.section.modulus_N_mm2 *= 2;
        beam.section.shear_modulus_N_mm2 *= 2;
      }
      auto stiff_model = FrameModel::make(mech, stiffer);
      ASSERT_TRUE(stiff_model.ok());
      auto half = stiff_model->compliance(pose);
      ASSERT_TRUE(half.ok());
      EXPECT_LT(frame_compliance_difference(2.0 * half->compliance, c->compliance, mech.platform_size_mm()),
                1e-12);
    }
  }
}

TEST(FrameModel, AFrameThatIsAMechanismIsASingularStiffnessMatrixAtTheFramesLine) {
  // A frame node joined to nothing that is fixed (the ring's nodes float): its part moves as a rigid body.
  std::string frame = R"(stiffness:
  struts: {stiffness_N_mm: 200000}
  frame:
    sections:
      tube: {modulus_N_mm2: 210000, shear_modulus_N_mm2: 81000, area_mm2: 4000, second_moment_x_mm4: 1.2e7, second_moment_y_mm4: 1.2e7, torsion_constant_mm4: 2.4e7}
    nodes:
      - {name: a, position_mm: [400, 0, -50]}
      - {name: b, position_mm: [-200, 346, -50]}
      - {name: c, position_mm: [-200, -346, -50]}
      - {name: ground, position_mm: [0, 0, -500], fixed: true}
    beams:
      - {from: a, to: b, section: tube}
      - {from: b, to: c, section: tube}
    base_joint_nodes: [a, a, b, b, c, c]
)";
  const Machine machine = test::machine_from_text(test::kCh5HexapodText + frame);
  ASSERT_FALSE(machine.stiffness.frame.empty());
  const int frame_line = test::appended_line(test::kCh5HexapodText) + 2;
  auto model = FrameModel::make(*machine.mechanism, machine.stiffness);
  ASSERT_FALSE(model.ok());
  const Error& error = model.error();
  EXPECT_EQ(error.code, ErrorCode::singular);
  EXPECT_NE(error.message.find(fmt::format("test.yaml:{}: stiffness.frame", frame_line)), std::string::npos)
      << error.message;
  EXPECT_NE(error.message.find("singular stiffness"), std::string::npos) << error.message;
  EXPECT_NE(error.message.find("mechanism"), std::string::npos) << error.message;
  EXPECT_NE(error.message.find("'a'"), std::string::npos) << error.message;
  EXPECT_EQ(error.location.file, "test.yaml");
  EXPECT_EQ(error.location.line, frame_line);
  EXPECT_EQ(error.location.key, "stiffness.frame");
  // Joined to the ground, the same frame holds.
  const std::size_t beams_end = frame.find("    base_joint_nodes");
  ASSERT_NE(beams_end, std::string::npos);
  const std::string held =
      frame.substr(0, beams_end) + "      - {from: c, to: ground, section: tube}\n" + frame.substr(beams_end);
  const Machine fixed = test::machine_from_text(test::kCh5HexapodText + held);
  auto holds = FrameModel::make(*fixed.mechanism, fixed.stiffness);
  ASSERT_TRUE(holds.ok()) << holds.error().message;
  EXPECT_TRUE(holds->compliance(fixed.mechanism->home()).ok());
  // The frame alone says the same.
  auto alone = stiffness::frame_displacements(machine.stiffness.frame,
                                              std::vector<stiffness::Vector6>(4, stiffness::Vector6::Zero()));
  ASSERT_FALSE(alone.ok());
  EXPECT_EQ(alone.error().code, ErrorCode::singular);
}

TEST(FrameModel, ExampleMachineWithAFrame) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5_frame.yaml");
  const Mechanism& mech = *machine.mechanism;
  ASSERT_FALSE(machine.stiffness.frame.empty());
  EXPECT_EQ(machine.stiffness.model, StiffnessModel::frame);
  auto model = FrameModel::make(mech, machine.stiffness);
  ASSERT_TRUE(model.ok()) << model.error().message;
  auto fe = model->compliance(mech.home());
  auto struts = stiffness::strut_compliance(mech, machine.stiffness, mech.home());
  ASSERT_TRUE(fe.ok() && struts.ok());
  // The frame adds compliance, but it is a stiff frame: less than the struts' own at home.
  const double frame_part = (fe->compliance - struts->compliance).norm();
  EXPECT_GT(frame_part, 0.0);
  EXPECT_LT(frame_part, struts->compliance.norm());
}

}  // namespace
}  // namespace pkm
