// SPDX-License-Identifier: MIT
// The list of binding doc texts (see doc.hpp).
#include "bindings/doc.hpp"

namespace smi::bind {

std::vector<DocText> binding_docs() {
  return {doc_vec(),        doc_mat(),         doc_rng(),       doc_csv_json(), doc_stats_dist(),
          doc_stats_kde(),  doc_stats_metric(), doc_surrogate(), doc_eval(),     doc_improve()};
}

}  // namespace smi::bind
