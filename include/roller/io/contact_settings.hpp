#pragma once
// A scene's words for its contact solves, typed: what a ContactSession (contact/contact_session.hpp)
// takes of the scene, so that the session itself knows no scene.
#include "roller/contact/contact_session.hpp"
#include "roller/io/scene.hpp"

namespace roller {

ContactSessionSettings contact_session_settings(const Scene& scene);

}  // namespace roller
