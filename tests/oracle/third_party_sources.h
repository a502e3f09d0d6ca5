// The original shader sources of ported methods, read at test time from the project's pinned
// copies (../shared/third_party, its README lists upstream, commit and licence): never copied
// into the repository.
#pragma once
#include <string>

namespace aalab::oracle {

/// Where the sources are: $AALAB_THIRD_PARTY_DIR if set, else <source dir>/../shared/third_party.
std::string ThirdPartyDir();

/// True when ThirdPartyDir()/<relative> is a regular file.
bool ThirdPartyHas(const std::string& relative);

/// The text of ThirdPartyDir()/<relative>; throws std::runtime_error naming the path when it
/// cannot be read.
std::string ReadThirdParty(const std::string& relative);

}  // namespace aalab::oracle
