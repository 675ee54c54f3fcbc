// Store library, the read side: a database field as an optional value (NULL: none).
#pragma once

#include <optional>
#include <pqxx/field>

namespace dtmf::store {

template <typename T>
std::optional<T> optional_field(const pqxx::field& field) {
  return field.is_null() ? std::nullopt : std::optional<T>(field.as<T>());
}

}  // namespace dtmf::store
