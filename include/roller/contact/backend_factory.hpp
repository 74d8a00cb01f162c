#pragma once
// The contact backend a scene asks for (contact.backend): the one place that knows every
// backend, so that the interface (contact/backend.hpp) knows none of them.
#include <memory>

#include "roller/contact/backend.hpp"
#include "roller/contact/contact_options.hpp"
#include "roller/solver/newton_options.hpp"

namespace roller {

// Throws InputError naming the option when the options are invalid. `newton` controls the
// penalty backend's Newton iterations (the scene's [newton] table).
std::unique_ptr<ContactBackend> make_contact_backend(const ContactOptions& options, const NewtonOptions& newton);

// The backend of a run's increments: the scene's contact backend with a roller, the strip's own
// Newton (StripBackend) without one.
std::unique_ptr<ContactBackend> make_increment_backend(bool roller, const ContactOptions& options,
                                                       const NewtonOptions& newton);

}  // namespace roller
