#include "packlab/mechanics/opal_materials.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "packlab/core/error.hpp"
#include "packlab/io/options.hpp"

namespace packlab::mechanics {

std::vector<dem::Material> opal_particle_types(const OpalMaterials& m) {
  const dem::Material silica{.friction = m.friction,
                             .density = m.silica_density,
                             .damping = m.damping,
                             .youngs_modulus = m.silica_youngs_modulus,
                             .poisson_ratio = m.silica_poisson_ratio,
                             .restitution = m.restitution,
                             .rolling_friction = m.rolling_friction};
  dem::Material titania = silica;
  titania.youngs_modulus = m.titania_youngs_modulus;
  titania.poisson_ratio = m.titania_poisson_ratio;
  titania.density = m.titania_density;
  std::vector<dem::Material> types(5, silica);
  types[static_cast<std::size_t>(particle_type::coating)] = titania;
  return types;
}

std::vector<dem::ElasticBond::Params> opal_bond_materials(const OpalMaterials& m) {
  dem::ElasticBond::Params silica{m.silica_youngs_modulus, m.silica_poisson_ratio, m.silica_strength,
                                  m.silica_strength,       m.bond_radius_ratio,    m.relaxation_time};
  dem::ElasticBond::Params titania{m.titania_youngs_modulus, m.titania_poisson_ratio, m.titania_strength,
                                   m.titania_strength,       m.bond_radius_ratio,     m.relaxation_time};
  silica.compressive_breakage = titania.compressive_breakage = m.compressive_breakage;
  return {silica, titania, silica};
}

void UniaxialCompressionSetup::finish(const Packing& model) {
  UniaxialCompressionSetup copy = *this;
  copy.options.on_point = nullptr;
  io::compression_test_options(copy).validate();
  options.types = opal_particle_types(materials);
  options.bond_materials = opal_bond_materials(materials);
  options.snapshot_strains = snapshot_strains;
  options.snapshot_stresses = snapshot_stresses;
  if (strain_rate > 0.0) {
    options.strain_rate = strain_rate;
    return;
  }
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t k = 0; k < model.size(); ++k) {
    lo = std::min(lo, model.position[k].z - model.radius[k]);
    hi = std::max(hi, model.position[k].z + model.radius[k]);
  }
  if (!(hi > lo)) fail_input("compression test: the model has no height");
  const double c = std::sqrt(materials.silica_youngs_modulus / materials.silica_density);
  options.strain_rate = quasi_static * c / (hi - lo);
}

}  // namespace packlab::mechanics
