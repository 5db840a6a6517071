#include "contact/cloth_contact.h"

namespace fse_sim {

// Defined beside their models (cloth_library_contact.cpp, cloth_mesh_contact.cpp).
std::unique_ptr<ContactDetector> makeLibraryContact(const ShapeSpec&, int, int,
                                                    const SimulationOptions&);
std::unique_ptr<ContactDetector> makeMeshContact(const ShapeSpec&, int, const SimulationOptions&);

std::unique_ptr<ContactDetector> makeContactDetector(const ShapeSpec& spec, int index,
                                                     int vertex_count,
                                                     const SimulationOptions& options) {
  if (options.model == ContactModel::kMesh) return makeMeshContact(spec, index, options);
  return makeLibraryContact(spec, index, vertex_count, options);
}

}  // namespace fse_sim
