// SPDX-License-Identifier: MIT
// The binding areas, one record each (modules.hpp): luaopen_smi opens them in this order and
// binding_docs() lists their reference texts in it.
#include "bindings/doc.hpp"
#include "bindings/modules.hpp"

namespace smi::bind {

const std::vector<Area>& areas() {
  static const std::vector<Area> kAreas = {
      {"vec", open_vec, {doc_vec}},
      {"mat", open_mat, {doc_mat}},
      {"rng", open_rng, {doc_rng}},
      {"csv", open_csv, {doc_csv_json}},  // csv_json_doc.cpp holds both modules' texts
      {"json", open_json, {}},
      {"stats", open_stats, {doc_stats_dist, doc_stats_kde, doc_stats_metric}},
      {"surrogate", open_surrogate, {doc_surrogate}},
      {"eval", open_eval, {doc_eval}},
      {"improve", open_improve, {doc_improve}},
      {"run", open_run, {doc_run}},
      {"members", open_members, {}},  // last: it wraps the module tables the others made
  };
  return kAreas;
}

std::vector<DocText> binding_docs() {
  std::vector<DocText> out;
  for (const Area& a : areas())
    for (auto doc : a.docs) out.push_back(doc());
  return out;
}

}  // namespace smi::bind

int luaopen_smi(lua_State* L) {
  lua_newtable(L);  // stack: [smi]
  for (const smi::bind::Area& a : smi::bind::areas()) a.open(L);
  return 1;
}
