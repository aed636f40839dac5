/* Status texts and names, generated from the one X-macro list in riemann.h. */
#include "sabre/riemann.h"

const char *rmn_strerror(int status) {
  switch (status) {
#define RMN_X_TEXT(name, value, text) \
  case name:                          \
    return text;
    RMN_STATUS_LIST(RMN_X_TEXT)
#undef RMN_X_TEXT
    default:
      return "unknown status";
  }
}

const char *rmn_status_name(int status) {
  switch (status) {
#define RMN_X_NAME(name, value, text) \
  case name:                          \
    return #name;
    RMN_STATUS_LIST(RMN_X_NAME)
#undef RMN_X_NAME
    default:
      return "RMN_UNKNOWN";
  }
}

const char *rmn_wave_name(enum rmn_wave wave) {
  switch (wave) {
    case RMN_WAVE_CONTACT:
      return "contact";
    case RMN_WAVE_EXPANSION:
      return "expansion";
    case RMN_WAVE_SHOCK:
      return "shock";
  }
  return "unknown";
}

const char *rmn_flow_name(enum rmn_flow flow) {
  return flow == RMN_FLOW_INFLOW ? "inflow" : "outflow";
}

const char *rmn_exact_wave_name(enum rmn_exact_wave wave) {
  return wave == RMN_EXACT_SHOCK ? "shock" : "rarefaction";
}
