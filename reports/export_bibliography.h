/// The sources aalab's methods and metrics come from, as BibTeX entries keyed by the
/// `source` field of the method and metric registries (methods/registry.cpp,
/// metrics/registry.cpp): `aalab export` writes the entries of every method and metric in its
/// tables to references.bib.
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace aalab {

/// The BibTeX entry of `key` (the whole "@type{key, ...}" text); UserError-free: an unknown
/// key is an internal error (a registry names a source this table lacks).
std::string BibEntry(const std::string& key);

/// Every key the table holds, in table order.
std::vector<std::string> BibKeys();

/// Splits a registry `source` field ("key1,key2") into keys; "" gives none.
std::vector<std::string> SourceKeys(const std::string& source);

/// references.bib: `provenance` as % comments, then for each (what, keys) a comment line
/// "what: keys" (what = "method fxaa-high", "metric edge_psnr_db"; "no published source"
/// when empty), then each distinct key's entry once, in first-use order, then an entry for
/// aalab itself (version and commit of this build).
std::string BibtexFile(const std::vector<std::pair<std::string, std::string>>& uses,
                       const std::vector<std::string>& provenance);

}  // namespace aalab
