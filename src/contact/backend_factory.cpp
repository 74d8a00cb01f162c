#include "roller/contact/backend_factory.hpp"

#include "roller/contact/ipopt_backend.hpp"
#include "roller/contact/penalty_backend.hpp"
#include "roller/contact/strip_backend.hpp"
#include "roller/core/error.hpp"

namespace roller {

std::unique_ptr<ContactBackend> make_contact_backend(const ContactOptions& options, const NewtonOptions& newton) {
  std::string why;
  if (!options.is_valid(&why)) throw InputError(why);
  if (options.backend == ContactBackendKind::Ipopt) return std::make_unique<IpoptBackend>(options, newton.linear);
  return std::make_unique<PenaltyBackend>(options, newton);
}

std::unique_ptr<ContactBackend> make_increment_backend(bool roller, const ContactOptions& options,
                                                       const NewtonOptions& newton) {
  if (!roller) return std::make_unique<StripBackend>(newton);
  return make_contact_backend(options, newton);
}

}  // namespace roller
