#pragma once
#include <memory>
// A scene's words for its contact solves, typed: what a ContactSession (contact/contact_session.hpp)
// takes of the scene, so that the session itself knows no scene.
#include "roller/contact/contact_session.hpp"
#include "roller/contact/elastic_roller.hpp"
#include "roller/io/scene.hpp"

namespace roller {

// `mesh`: the strip's, whose surface spacing sets an elastic roller's rim mesh.
ContactSessionSettings contact_session_settings(const Scene& scene, const Mesh& mesh);

// An elastic roller's rim arc: 4 two-body Hertz half-widths either side of the lowest point for
// the path's largest force (or the geometric half-width of its deepest press), at least ten of the
// strip's surface spacings, the spacing the strip's finest along its top.
RimArc elastic_rim_arc(const Scene& scene, const Mesh& mesh);

// The scene's elastic roller (its [roller] E, nu, inner_radius and radius); the scene has one.
ElasticRollerSpec elastic_roller_spec(const Scene& scene);

// The scene's elastic roller condensed onto that arc; null for a rigid roller.
std::shared_ptr<const RimStiffness> elastic_rim(const Scene& scene, const Mesh& mesh);

}  // namespace roller
