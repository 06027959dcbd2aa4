// Tool detection: the contact elements between the fibres and the rigid tools at the current
// state (once per loop A pass, like fibre-fibre detection).
//
// Reads  FibreStore (q), ToolStore, ContactParams (tool proximity), IterationInput (time).
// Writes ToolContactStore (overwritten; the friction reference is left to
//        systems/friction_reference.h).
// Along every fibre element, at its Gauss points (2 per quadratic element, z = -+1/sqrt(3); 1 per
// linear, z = 0), each carrying h / points of the centreline, so that a uniform line pressure
// gives the nodes the consistent line load exactly), a contact element is made when the centreline is
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

void detectToolContacts(const FibreStore& fibres, const ToolStore& tools,
                        const ContactParams& params, const IterationInput& input,
                        ToolContactStore& contacts);

}  // namespace fibra
