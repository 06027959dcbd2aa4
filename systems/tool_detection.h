// Tool detection: the contact elements between the fibres and the rigid tools at the current
// state (once per loop A pass, like fibre-fibre detection).
//
// Reads  FibreStore (q), ToolStore, ContactParams (tool proximity), IterationInput (time).
// Writes ToolContactStore (overwritten; the friction reference is left to
//        systems/friction_reference.h).
// Along every fibre element, at its n Gauss points (toolPointsPerElement: 2 per quadratic element
// and 1 per linear on a plane, more on a cylinder), each carrying w h / 2 of the centreline (w its
// Gauss weight), so that a uniform line pressure gives the nodes the consistent line load
// exactly), a contact element is made when the centreline is
// within R + Delta of the surface (Delta: the scene's proximity distance; by default
// max(R, h/2), h the element length, so that a fibre approaching the tool has elements before it
// arrives); its particle is the outline point facing the tool (paper Fig. 4 with the direction
// -N), its normal N the surface normal at the closest point (towards the fibre), its tool point
// the surface point under the particle, kept as a material point of the tool.
// A fibre is cut flat at its end sections: at each end whose section centre is within R + Delta
// of the surface, the end face's centre and 8 points of its rim (xi = R (cos phi, sin phi)) are
// particles too, so an end pushed onto a tool stands on it.
// Serial, tools then elements in order: tool contacts are few.
#pragma once

#include "components/contact_params.h"
#include "components/iteration.h"
#include "components/tools.h"

namespace fibra {

// The most Gauss points a fibre element takes against one tool.
constexpr int kMaxToolPoints = 32;

// The smallest radius of curvature of a tool's convex surface, mm: a cylinder's radius with the
// fibres outside it; infinite for a plane and for a cylinder with the fibres inside (a chord
// between two points on a concave wall moves away from it).
double toolCurvatureRadius(const ToolStore& tools, Index tool);

// The sagitta s^2 / (8 rho) over the widest spacing s of n Gauss points per element of length h
// (between neighbours and across the element's ends; mm, mm, -): how deep a straight fibre
// across a convex surface of radius rho can be overlapped between two points beyond what they
// see, wherever the crest falls, mm.
double toolSagittaBound(double h, double rho, int n);

// Gauss points per element of length h (mm, order 1 or 2) against a surface of smallest radius
// of curvature rho (mm, infinite: the element's own rule) and p_max (mm): the fewest, from
// `order` up, whose sagitta bound is at most p_max / 4 (widest spacing s <= sqrt(2 rho p_max));
// kMaxToolPoints at most, where the bound may exceed p_max / 4 (fibra check says by how much).
int toolPointsPerElement(double h, double rho, double pMax, int order);

void detectToolContacts(const FibreStore& fibres, const ToolStore& tools,
                        const ContactParams& params, const IterationInput& input,
                        ToolContactStore& contacts);

}  // namespace fibra
