#include "tribos/stack/ContactFields.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tribos/contact/ContactSolver.hpp"
#include "tribos/stack/GlobalFields.hpp"
#include "tribos/stack/RootGather.hpp"

namespace tribos::stack {

const std::array<ContactNodalField, 16> kContactNodalFields = {{
    {"contact_normal", &ContactFields::contactNormal},
    {"contact_t1", &ContactFields::contactT1},
    {"contact_t2", &ContactFields::contactT2},
    {"contact_status", &ContactFields::contactStatus},
    {"contact_pressure", &ContactFields::contactPressure},
    {"contact_gap", &ContactFields::contactGap},
    {"contact_opening", &ContactFields::contactOpening},
    {"contact_nx", &ContactFields::contactNx},
    {"contact_ny", &ContactFields::contactNy},
    {"contact_nz", &ContactFields::contactNz},
    {"contact_master", &ContactFields::contactMaster},
    {"contact_slip_t1", &ContactFields::contactSlipT1},
    {"contact_slip_t2", &ContactFields::contactSlipT2},
    {"contact_tangential_t1", &ContactFields::contactTangentialT1},
    {"contact_tangential_t2", &ContactFields::contactTangentialT2},
    {"contact_accumulated_slip", &ContactFields::contactAccumulatedSlip},
}};

const char* nameOf(std::vector<double> ContactFields::*values) {
  for (const auto& field : kContactNodalFields)
    if (field.values == values) return field.name;
  throw std::logic_error("tribos::stack::nameOf: not a field of kContactNodalFields");
}

double contactMemorySum(const std::vector<double>& tangentialT1, const std::vector<double>& tangentialT2,
                        const std::vector<double>& accumulatedSlip) {
  double sum = 0.0;
  for (size_t n = 0; n < tangentialT1.size(); ++n)
    sum += std::abs(tangentialT1[n]) + std::abs(tangentialT2[n]) + std::abs(accumulatedSlip[n]);
  return sum;
}

// Every contact node's rows belong to one rank, which sends its forces, status and opening;
// each interface's resultants and extremes are summed from them on rank 0.
void gatherContactFields(const Scene& scene, const feti::ConstraintMatrix& B,
                         const std::vector<contact::ContactNodeResult>& nodes, MPI_Comm comm, ContactFields& out) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  out.interfaces.clear();  // every rank: names and laws (the sums below are rank 0's)
  for (const auto& one : scene.contacts)
    out.interfaces.push_back({one.rows.name, one.rows.slaveSideSet + " -> " + one.rows.masterSideSet, one.law});
  const size_t numNodes = static_cast<size_t>(scene.mesh.numNodes());
  constexpr int kPerNode = 7;  // force (nu, t1, t2), status, opening, tangential relative displacement (t1, t2)
  Records mine;  // one per contact node of this rank's rows
  mine.width = kPerNode;
  for (const auto& node : nodes) {
    const double f[kPerNode] = {node.force[0], node.force[1], node.force[2], static_cast<double>(node.status),
                                node.opening, node.relativeDisplacement[1], node.relativeDisplacement[2]};
    mine.add(node.slaveNode, f);
  }
  const Records gathered = gatherToRoot(mine, comm);
  if (rank != 0) return;
  std::vector<double> all(kPerNode * numNodes, 0.0);
  for (size_t k = 0; k < gathered.size(); ++k)
    std::copy_n(&gathered.values[kPerNode * k], kPerNode, &all[kPerNode * static_cast<size_t>(gathered.index[k])]);
  for (const auto& field : kContactNodalFields) (out.*field.values).assign(numNodes, 0.0);
  std::vector<std::vector<double>> area;  // per interface: the tributary area of its slave nodes
  for (const auto& one : scene.contacts) area.push_back(tributaryArea(scene.mesh, one.rows.slaveSideSet));
  for (const auto& c : B.contact) {
    const size_t g = static_cast<size_t>(c.slaveNode);
    const double* f = all.data() + kPerNode * g;
    const double a = area[c.interface][g];
    out.contactNormal[g] = f[0];
    out.contactT1[g] = f[1];
    out.contactT2[g] = f[2];
    out.contactStatus[g] = f[3];
    out.contactOpening[g] = f[4];
    out.contactPressure[g] = a > 0.0 ? f[0] / a : 0.0;
    out.contactGap[g] = c.gap;
    out.contactNx[g] = c.normal[0];
    out.contactNy[g] = c.normal[1];
    out.contactNz[g] = c.normal[2];
    out.contactMaster[g] = static_cast<double>(c.masterNode + 1);
    out.contactSlipT1[g] = out.contactTangentialT1[g] = f[5];
    out.contactSlipT2[g] = out.contactTangentialT2[g] = f[6];
    out.totalNormalForce += f[0];
    InterfaceResult& i = out.interfaces[c.interface];
    i.normalForce += f[0];
    for (int x = 0; x < 3; ++x) {
      const double fx = f[0] * c.normal[x] + f[1] * c.t1[x] + f[2] * c.t2[x];
      out.totalContactForce[x] += fx;
      i.force[x] += fx;
    }
    i.frictionForce += std::hypot(f[1], f[2]);
    ++i.counts[static_cast<int>(f[3])];
    i.peakPressure = std::max(i.peakPressure, out.contactPressure[g]);
    i.largestOpening = std::max(i.largestOpening, f[4]);
    i.largestOverlap = std::max(i.largestOverlap, -f[4]);
    if (static_cast<int>(f[3]) == static_cast<int>(contact::ContactStatus::Slip)) {
      // The work of friction over the slip (the step's end force times its increment: the
      // incremental rule of a load history), >= 0 by the slip rule.
      out.contactAccumulatedSlip[g] = std::hypot(f[5], f[6]);
      i.stepDissipation += f[1] * f[5] + f[2] * f[6];
    }
  }
  for (auto& i : out.interfaces) {
    i.dissipatedEnergy = i.stepDissipation;
    out.dissipatedEnergy += i.stepDissipation;
  }
}

namespace {
/// The increment since `before` of the relative tangential displacement of contact node c's
/// row, u_slave - sum_j w_j u_master_j, along t1 (j = 0) and t2 (j = 1), from the kinematics.
std::array<double, 2> kinematicIncrement(const feti::ContactNode& c,
                                         const std::vector<std::array<double, 3>>& displacement,
                                         const ContactFields* before) {
  std::array<double, 3> relative{0.0, 0.0, 0.0};
  for (const auto& [node, weight] : c.sides())
    for (int x = 0; x < 3; ++x) relative[x] += weight * displacement[node][x];
  const size_t g = static_cast<size_t>(c.slaveNode);
  std::array<double, 2> increment{};
  for (int j = 0; j < 2; ++j) {
    const auto& t = j == 0 ? c.t1 : c.t2;
    const double total = relative[0] * t[0] + relative[1] * t[1] + relative[2] * t[2];
    double totalBefore = 0.0;
    if (before) {
      const auto& field = j == 0 ? before->contactTangentialT1 : before->contactTangentialT2;
      if (g < field.size()) totalBefore = field[g];
    }
    increment[j] = total - totalBefore;
  }
  return increment;
}
}  // namespace

void addKinematicSlip(const Scene& scene, const feti::ConstraintMatrix& B,
                      const std::vector<std::array<double, 3>>& displacement, const ContactFields* before,
                      ContactFields& out) {
  if (displacement.empty() || out.contactSlipT1.size() != displacement.size()) return;  // not rank 0
  for (const auto& c : B.contact) {
    if (scene.contacts[c.interface].law.hasTangentialRows()) continue;
    const size_t g = static_cast<size_t>(c.slaveNode);
    const std::array<double, 2> increment = kinematicIncrement(c, displacement, before);
    out.contactSlipT1[g] = out.contactTangentialT1[g] = increment[0];
    out.contactSlipT2[g] = out.contactTangentialT2[g] = increment[1];
    if (static_cast<int>(out.contactStatus[g]) == static_cast<int>(contact::ContactStatus::Slip))
      out.contactAccumulatedSlip[g] = std::hypot(increment[0], increment[1]);
  }
}

std::array<int, 3> addPrescribedSlipFriction(const Scene& scene, const feti::ConstraintMatrix& B,
                                             const std::vector<std::array<double, 3>>& displacement,
                                             const ContactFields* before, std::vector<std::array<double, 3>>& reaction,
                                             ContactFields& out) {
  std::array<int, 3> change{0, 0, 0};
  if (displacement.empty() || out.contactSlipT1.size() != displacement.size()) return change;  // not rank 0
  const int slip = static_cast<int>(contact::ContactStatus::Slip);
  for (const auto& c : B.contact) {
    const size_t g = static_cast<size_t>(c.slaveNode), m = static_cast<size_t>(c.masterNode);
    const int status = static_cast<int>(out.contactStatus[g]);
    if ((!c.slipPrescribed[0] && !c.slipPrescribed[1]) || status == static_cast<int>(contact::ContactStatus::NoContact))
      continue;
    InterfaceResult& i = out.interfaces[c.interface];
    i.frictionForce -= std::hypot(out.contactT1[g], out.contactT2[g]);
    double size = 0.0;  // of the displacements the increment is a difference of (round-off scale)
    for (int x = 0; x < 3; ++x) size += std::abs(displacement[g][x]) + std::abs(displacement[m][x]);
    bool slides = false;
    for (int j = 0; j < 2; ++j) {
      if (!c.slipPrescribed[j]) continue;
      const auto& t = j == 0 ? c.t1 : c.t2;
      auto& total = j == 0 ? out.contactTangentialT1 : out.contactTangentialT2;
      double relative = 0.0;
      for (int x = 0; x < 3; ++x) relative += (displacement[g][x] - displacement[m][x]) * t[x];
      const double increment = relative - (before && g < total.size() ? (j == 0 ? before->contactTangentialT1
                                                                                : before->contactTangentialT2)[g]
                                                                       : 0.0);
      if (!(std::abs(increment) > 1e-10 * size)) continue;  // held still: no slip
      slides = true;
      // The force of the slave on the master along t_j: with the slip (the slave drags the master).
      const double force = std::copysign(scene.contacts[c.interface].law.slidingForce(j, out.contactNormal[g]), increment);
      (j == 0 ? out.contactT1 : out.contactT2)[g] = force;
      (j == 0 ? out.contactSlipT1 : out.contactSlipT2)[g] = total[g] = increment;
      for (int x = 0; x < 3; ++x) {
        out.totalContactForce[x] += force * t[x];
        i.force[x] += force * t[x];
        // As addDroppedContactForces (GlobalFields.cpp): the supports of the held components take it.
        reaction[g][x] += t[x] * force;
        reaction[m][x] -= t[x] * force;
      }
      i.stepDissipation += force * increment;
      i.dissipatedEnergy += force * increment;
      out.dissipatedEnergy += force * increment;
    }
    i.frictionForce += std::hypot(out.contactT1[g], out.contactT2[g]);
    if (!slides) continue;
    out.contactAccumulatedSlip[g] = std::hypot(out.contactSlipT1[g], out.contactSlipT2[g]);
    if (status == slip) continue;
    --i.counts[status];
    ++i.counts[slip];
    --change[status];
    ++change[slip];
    out.contactStatus[g] = slip;
  }
  return change;
}

void addEarlierSteps(const ContactFields& previous, ContactFields& now) {
  for (size_t g = 0; g < now.contactTangentialT1.size(); ++g) {
    now.contactTangentialT1[g] += previous.contactTangentialT1[g];
    now.contactTangentialT2[g] += previous.contactTangentialT2[g];
    now.contactAccumulatedSlip[g] += previous.contactAccumulatedSlip[g];
  }
  for (size_t i = 0; i < now.interfaces.size(); ++i)
    now.interfaces[i].dissipatedEnergy += previous.interfaces[i].dissipatedEnergy;
  now.dissipatedEnergy += previous.dissipatedEnergy;
}

std::vector<contact::ContactNodeResult> tiedNodeResults(const feti::ConstraintMatrix& B, int rank,
                                                        const std::vector<double>& ownedLambda,
                                                        const std::vector<double>& ownedResidual) {
  std::vector<contact::ContactNodeResult> out;
  const GO first = B.firstRowOfRank[rank], end = B.firstRowOfRank[rank + 1];
  for (const auto& node : B.contact) {
    if (node.normalRow < first || node.normalRow >= end) continue;
    contact::ContactNodeResult r;
    r.slaveNode = node.slaveNode;
    r.status = contact::ContactStatus::Stick;
    const size_t n = static_cast<size_t>(node.normalRow - first);
    r.force[0] = node.rowScale * ownedLambda[n];
    r.opening = -ownedResidual[n] / node.rowScale;
    for (int j = 0; j < 2; ++j)
      if (const GO t = node.tangentialRow(j); t >= 0)
        r.force[j + 1] = node.tangentialScale[j] * ownedLambda[static_cast<size_t>(t - first)];
    out.push_back(r);
  }
  return out;
}

}  // namespace tribos::stack
