// Broadphase: candidate element pairs whose centrelines may come within Delta_prox.
//
// Reads  FibreStore (topology, radii), the state q (x0 of the nodes), ContactParams (reach,
//        skin, self-contact), the cancel flag (per query chunk).
// Writes CentrelineStore (every call: per element polynomial x0(z) and control-point box) and
//        BroadphaseCache (candidate pairs, grid, skin reference; on rebuild only).
// Threading: parallel over elements and grid buckets (oneTBB, the caller's arena). Bucket
//        contents are sorted and candidates are written per fixed element chunk, so the
//        candidate set and its order do not depend on the thread count.
//
// Bound: a quadratic centreline lies in the convex hull of its Bernstein control points
// (a - b + c, a - c, a + b + c for x(z) = a + b z + c z^2), a linear one on its chord. The box
// of element e of fibre f is that hull's box inflated by reach_f + Lambda skin / 2, rounded
// outwards to float. Two centreline points closer than Delta_prox(I, J) = reach_I + reach_J are
// closer in every coordinate, so their elements' boxes overlap: no zone can be missed.
// Skin: when every node moved at most skin / 2 since the last rebuild, every centreline point
// moved at most Lambda skin / 2 (Lambda = max sum |N_a| = 1 linear, 1.25 quadratic), so the old
// boxes still bound the current centrelines and the candidate set is reused.
//
// Grid: cell size = mean box extent; each box is entered in every cell it overlaps (dense
// array, or a hash table when the dense grid would exceed 2 cells per element); element A
// then scans the cells of its box for B > A and reports the pair only in the cell holding the
// lower corner max(lo_A, lo_B) of the intersection, hence exactly once.
// Pairs kept: distinct fibres; on one fibre (self-contact only) elements i < j with
// (j - i + 1) h >= separation, i.e. some s' in j lies at least the separation beyond some s in i.
#pragma once

#include "components/contact_cache.h"
#include "core/cancel.h"
#include "core/trace.h"
#include "systems/contact_params.h"

namespace fibra {

// Updates the centrelines and, unless the skin test allows reuse, the candidate pairs.
// Returns whether the candidate set was rebuilt (also in cache.rebuilt). Cancelled (checked per
// query chunk): returns early with an incomplete candidate set, marked invalid.
bool updateBroadphase(const FibreStore& fs, const Eigen::VectorXd& q, const ContactParams& params,
                      CentrelineStore& centrelines, BroadphaseCache& cache, Trace* trace,
                      const Cancel& cancel);

}  // namespace fibra
