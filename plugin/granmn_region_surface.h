/* -*- c++ -*- ----------------------------------------------------------
   The surface of a LAMMPS region as a wall sees it: the faces within reach of a point
   (Region::surface), each with the plain region (a part: not a union or intersect) it is a
   face of, so that a contact can take the velocity of the part that moves.

   A union or intersect is walked here from its members, by the rules of LAMMPS's RegUnion and
   RegIntersect (a member's face is kept where no other member covers it, or where all the
   others do; an exterior one, side out, from the members' exteriors; the faces numbered as
   LAMMPS numbers them), with the members' own Region::surface and Region::match. LAMMPS's
   union and intersect cannot serve a moving member: those of 29 Sep 2021 and 4 Feb 2025 pass
   no member's velocity on (an intersect gives none, a union its own, which nothing sets), and
   a union with a rotating member applies a rotation of its own whose angle and axis are never
   set; those of 4 Jul 2026 pass the members' velocities on but transform a rotating member's
   contacts a second time. The union of 29 Sep 2021 also reports an exterior face's distance
   as 0.
------------------------------------------------------------------------- */

#ifndef LMP_GRANMN_REGION_SURFACE_H
#define LMP_GRANMN_REGION_SURFACE_H

#include "domain.h"
#include "granmn_compat.h"
#include "region.h"

#include <cstring>
#include <string>
#include <vector>

namespace granmn {

// A face within reach of a point: LAMMPS's Region::Contact, and the part it belongs to.
struct SurfaceContact {
  double r;                   // distance from the face's nearest point to the point
  double delx, dely, delz;    // from that nearest point to the point
  int iwall;                  // the face's number in the whole region
  int part;                   // the part it is a face of (RegionSurface::parts)
};

class RegionSurface {
 public:
  // The region's parts and members, found anew (a deck may define regions again between runs).
  void assign(LAMMPS_NS::Domain *domain, LAMMPS_NS::Region *region)
  {
    nodes.clear();
    plain.clear();
    face_layout.clear();
    add(domain, region);
    single = nodes.size() == 1 ? region : nullptr;
  }
  LAMMPS_NS::Region *region() const { return nodes[0].region; }
  // The plain regions it is made of (itself if it is one), each once, in the order walked.
  const std::vector<LAMMPS_NS::Region *> &parts() const { return plain; }
  // How its faces are numbered: the styles, sides and face counts of its parts as they are
  // combined; two regions of one layout give the same face the same number.
  const std::string &layout() const { return face_layout; }

  // Region::match: whether x is on the region's side of its surface.
  bool match(const double *x)
  {
    return single ? single->match(x[0], x[1], x[2]) : matches(0, x);
  }
  // Region::surface: the faces within cutoff of x, contact(0 .. n - 1). A plain region's are
  // read from its own contacts, those of a union or intersect from the walk's.
  int surface(const double *x, double cutoff)
  {
    if (single) return single->surface(x[0], x[1], x[2], cutoff);
    found.clear();
    collect(0, x, cutoff);
    return static_cast<int>(found.size());
  }
  SurfaceContact contact(int k) const
  {
    if (!single) return found[k];
    const LAMMPS_NS::Region::Contact &c = single->contact[k];
    return {c.r, c.delx, c.dely, c.delz, c.iwall, 0};
  }

  // A part's rotation point and unit axis (Region keeps them protected; a pointer to the member
  // formed through a derived class reads them without changing LAMMPS).
  static const double *rotation_point(const LAMMPS_NS::Region *part)
  {
    return part->*(&RotationOf::point);
  }
  static const double *rotation_axis(const LAMMPS_NS::Region *part)
  {
    return part->*(&RotationOf::runit);
  }

 private:
  struct Node {
    LAMMPS_NS::Region *region;
    bool is_union;               // a union (else an intersect, or a part)
    int part;                    // a part's index in plain, else -1
    std::vector<int> members;    // a union's or intersect's member nodes
  };
  struct RotationOf : LAMMPS_NS::Region {
    using LAMMPS_NS::Region::point;
    using LAMMPS_NS::Region::runit;
  };

  std::vector<Node> nodes;    // nodes[0]: the region
  LAMMPS_NS::Region *single = nullptr;    // the region if it is a plain one
  std::vector<LAMMPS_NS::Region *> plain;
  std::string face_layout;
  std::vector<SurfaceContact> found;

  static bool combines(const LAMMPS_NS::Region *region)
  {
    return strcmp(region->style, "union") == 0 || strcmp(region->style, "intersect") == 0;
  }

  int add(LAMMPS_NS::Domain *domain, LAMMPS_NS::Region *region)
  {
    const int node = static_cast<int>(nodes.size());
    nodes.push_back({region, strcmp(region->style, "union") == 0, -1, {}});
    face_layout += fmt::format("{} {} {}", region->style, region->interior ? "in" : "out",
                               region->cmax);
    if (!combines(region)) {
      int part = 0;
      while (part < static_cast<int>(plain.size()) && plain[part] != region) part++;
      if (part == static_cast<int>(plain.size())) plain.push_back(region);
      nodes[node].part = part;
      return node;
    }
    face_layout += " (";
    std::vector<int> members;
    for (int k = 0; k < region->nregion; k++) {
      if (k) face_layout += ", ";
      members.push_back(add(domain, region_member(domain, region, k)));
    }
    face_layout += ")";
    nodes[node].members = members;
    return node;
  }

  bool matches(int node, const double *x)
  {
    const Node &n = nodes[node];
    if (n.members.empty()) return n.region->match(x[0], x[1], x[2]);
    if (n.region->openflag) return true;
    bool inside = !n.is_union;
    for (int member : n.members)
      if (matches(member, x) == n.is_union) {
        inside = n.is_union;
        break;
      }
    return inside == (n.region->interior != 0);
  }

  void collect(int node, const double *x, double cutoff)
  {
    const Node &n = nodes[node];
    LAMMPS_NS::Region *region = n.region;
    if (n.members.empty()) {
      const int count = region->surface(x[0], x[1], x[2], cutoff);
      for (int m = 0; m < count; m++) {
        const LAMMPS_NS::Region::Contact &c = region->contact[m];
        found.push_back({c.r, c.delx, c.dely, c.delz, c.iwall, n.part});
      }
    } else if (region->openflag) {
      // as Region::surface: one of the two finds none
      exterior_faces(node, x, cutoff);
      interior_faces(node, x, cutoff);
    } else if (region->interior) {
      interior_faces(node, x, cutoff);
    } else {
      exterior_faces(node, x, cutoff);
    }
  }

  // The faces of member k of `node` found for x since `first`, kept where `kept_at(other
  // member, the face's nearest point)` holds for every other member, numbered by `number`.
  template <typename Keep, typename Number>
  void keep_faces(int node, size_t k, size_t first, const double *x, Keep kept_at,
                  Number number)
  {
    const Node &n = nodes[node];
    size_t kept = first;
    for (size_t c = first; c < found.size(); c++) {
      const double xs[3] = {x[0] - found[c].delx, x[1] - found[c].dely, x[2] - found[c].delz};
      bool keep = true;
      for (size_t j = 0; j < n.members.size() && keep; j++)
        if (j != k) keep = kept_at(n.members[j], xs);
      if (!keep) continue;
      SurfaceContact face = found[c];
      face.iwall = number(face.iwall);
      found[kept++] = face;
    }
    found.resize(kept);
  }

  // RegUnion/RegIntersect::surface_interior: a member's faces numbered after those of the
  // members before it (each has cmax numbers).
  void interior_faces(int node, const double *x, double cutoff)
  {
    const Node &n = nodes[node];
    int offset = 0;
    for (size_t k = 0; k < n.members.size(); k++) {
      const size_t first = found.size();
      collect(n.members[k], x, cutoff);
      if (n.is_union)
        keep_faces(node, k, first, x, [this](int other, const double *xs) {
          return !(matches(other, xs) && !nodes[other].region->openflag);
        }, [offset](int iwall) { return iwall + offset; });
      else
        keep_faces(node, k, first, x, [this](int other, const double *xs) {
          return matches(other, xs);
        }, [offset](int iwall) { return iwall + offset; });
      offset += nodes[n.members[k]].region->cmax;
    }
  }

  // RegUnion/RegIntersect::surface_exterior: the members' exteriors (their sides flipped
  // meanwhile, as LAMMPS does), a face numbered by its member.
  void exterior_faces(int node, const double *x, double cutoff)
  {
    const Node &n = nodes[node];
    for (int member : n.members) nodes[member].region->interior ^= 1;
    for (size_t k = 0; k < n.members.size(); k++) {
      const size_t first = found.size();
      collect(n.members[k], x, cutoff);
      const int number = static_cast<int>(k);
      if (n.is_union)
        keep_faces(node, k, first, x, [this](int other, const double *xs) {
          return matches(other, xs);
        }, [number](int) { return number; });
      else
        keep_faces(node, k, first, x, [this](int other, const double *xs) {
          return !matches(other, xs);
        }, [number](int) { return number; });
    }
    for (int member : n.members) nodes[member].region->interior ^= 1;
  }
};

}    // namespace granmn

#endif
