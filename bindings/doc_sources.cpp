// The list of binding doc texts (see doc.hpp) and the placeholder filler they share.
#include <fmt/format.h>

#include "bindings/doc.hpp"
#include "kernels/core/errors.hpp"

namespace smi::bind {

std::string fill(std::string_view text, std::initializer_list<std::pair<std::string_view, std::string>> values) {
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t at = text.find("${", i);
    if (at == std::string_view::npos) {
      out.append(text.substr(i));
      break;
    }
    out.append(text.substr(i, at - i));
    const std::size_t end = text.find('}', at);
    if (end == std::string_view::npos) throw Error("doc text: unclosed ${ placeholder");
    const std::string_view key = text.substr(at + 2, end - at - 2);
    bool found = false;
    for (const auto& [k, v] : values)
      if (k == key) {
        out.append(v);
        found = true;
        break;
      }
    if (!found) throw Error(fmt::format("doc text: no value for placeholder ${{{}}}", key));
    i = end + 1;
  }
  return out;
}

std::string num(double v) { return fmt::format("{:.10g}", v); }

std::vector<DocText> binding_docs() {
  return {doc_vec(),        doc_mat(),         doc_rng(),       doc_csv_json(), doc_stats_dist(),
          doc_stats_kde(),  doc_stats_metric(), doc_surrogate(), doc_eval(),     doc_improve()};
}

}  // namespace smi::bind
