// certipose/occlusion/resting_contact.hpp — which facets of a part lie face to face on an
// occluder: the underside of a part standing on its fixture plate. Such a facet faces into the
// occluder it rests on, so a camera would have to be inside the fixture to see it; the paver only
// ever finds BOUNDARY boxes near it (the sight lines graze the plate), which a report must not
// present as "a finer ε may help".
//
// The test is exact (CGAL's filtered predicates on the input coordinates, no constructed point):
// a facet rests on the occluders when each of its three corners lies in the closed triangle of
// some occluder triangle that is coplanar with the facet and faces the other way. It labels
// facets in reports; it certifies nothing and removes nothing from a certificate.
//
// The definition, with CGAL, is in occlusion/cgal_resting_contact.hpp: compiled into
// certipose::precompiled (certipose/cgal.hpp), or included here in a header-only build.
#pragma once

#include "certipose/detail/config.hpp"
#include "certipose/geometry/triangle_mesh.hpp"

#include <span>
#include <vector>

namespace certipose {

/// For each facet of `part` with `ask[f]` set (all when `ask` is empty): whether it rests face to
/// face on a triangle of `occluders` (see the header comment). Degenerate triangles rest on
/// nothing and hold nothing up.
CERTIPOSE_DECL std::vector<char> resting_on_occluders(const triangle_mesh& part, std::span<const triangle_mesh> occluders,
                                                      const std::vector<char>& ask = {});

}  // namespace certipose

#if !defined(CERTIPOSE_PRECOMPILED)
#include "certipose/occlusion/cgal_resting_contact.hpp"
#endif
