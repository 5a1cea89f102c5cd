#include "comply/model/data.hpp"

#include "comply/model/model.hpp"

namespace comply::model {

Data::Data(const Model& model) {
  const int dof = model.dof();
  jacobian.setZero(6, dof);
  gravity.setZero(dof);
  coriolis.setZero(dof);
  mass_matrix.setZero(dof, dof);
  payload_gravity.setZero(dof);
}

}  // namespace comply::model
