#include "roller/contact/backend_factory.hpp"

#include "roller/contact/ipopt_backend.hpp"
#include "roller/contact/penalty_backend.hpp"
#include "roller/core/error.hpp"

namespace roller {

std::unique_ptr<ContactBackend> make_contact_backend(const ContactOptions& options, const NewtonOptions& newton) {
  std::string why;
  if (!options.is_valid(&why)) throw InputError(why);
  if (options.backend == ContactBackendKind::Ipopt) return std::make_unique<IpoptBackend>(options, newton.linear);
  return std::make_unique<PenaltyBackend>(options, newton);
}

}  // namespace roller
