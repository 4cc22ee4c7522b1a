/* The parts of RFC 8259 that cJSON does not enforce, checked on the text before it is parsed:
 * numbers follow the grammar  -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?  (cJSON hands any
 * run of [0-9+-.eE] to strtod, so 050 and 1. pass), strings hold well-formed UTF-8
 * (RFC 3629 §4: no overlong forms, no surrogates, nothing above U+10FFFF) and no raw control
 * characters (RFC 8259 §7). What cJSON itself checks (structure, escapes) is left to it. */
#include "core/internal.h"

/* Length of the well-formed UTF-8 sequence at s (lead byte >= 0x80), 0 when it is not. */
static size_t utf8_length(const unsigned char *s) {
  const unsigned c = s[0];
  size_t n;
  unsigned lo = 0x80, hi = 0xBF; /* allowed range of the second byte (RFC 3629 §4) */
  if (c >= 0xC2 && c <= 0xDF) {
    n = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    n = 3;
    if (c == 0xE0) lo = 0xA0;
    if (c == 0xED) hi = 0x9F; /* no surrogates */
  } else if (c >= 0xF0 && c <= 0xF4) {
    n = 4;
    if (c == 0xF0) lo = 0x90;
    if (c == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (s[1] < lo || s[1] > hi) return 0;
  for (size_t k = 2; k < n; ++k)
    if (s[k] < 0x80 || s[k] > 0xBF) return 0;
  return n;
}

static int is_digit(unsigned char c) { return c >= '0' && c <= '9'; }

/* Length of the number token at s, or 0 with *why set when it breaks the grammar. */
static size_t number_length(const unsigned char *s, const char **why) {
  size_t i = 0;
  if (s[i] == '-') ++i;
  if (!is_digit(s[i])) return *why = "a minus sign without digits", 0;
  if (s[i] == '0' && is_digit(s[i + 1])) return *why = "a number with a leading zero", 0;
  while (is_digit(s[i])) ++i;
  if (s[i] == '.') {
    ++i;
    if (!is_digit(s[i])) return *why = "a decimal point without digits after it", 0;
    while (is_digit(s[i])) ++i;
  }
  if (s[i] == 'e' || s[i] == 'E') {
    ++i;
    if (s[i] == '+' || s[i] == '-') ++i;
    if (!is_digit(s[i])) return *why = "an exponent without digits", 0;
    while (is_digit(s[i])) ++i;
  }
  return i;
}

size_t gm_json_check_text(const char *text, const char **why) {
  const unsigned char *s = (const unsigned char *)text;
  size_t i = 0;
  *why = NULL;
  while (s[i] != '\0') {
    if (s[i] == '"') {
      for (++i; s[i] != '"'; ++i) {
        if (s[i] == '\0') return i; /* unterminated: cJSON says so */
        if (s[i] == '\\') {
          if (s[i + 1] == '\0') return i + 1;
          ++i;
        } else if (s[i] < 0x20) {
          *why = "a raw control character in a string (write it as \\u00XX)";
          return i;
        } else if (s[i] >= 0x80) {
          size_t n = utf8_length(s + i);
          if (n == 0) {
            *why = "bytes that are not UTF-8 in a string";
            return i;
          }
          i += n - 1;
        }
      }
      ++i;
    } else if (s[i] == '-' || is_digit(s[i])) {
      size_t n = number_length(s + i, why);
      if (n == 0) return i;
      i += n;
    } else if (s[i] >= 0x80) {
      *why = "a byte that is not ASCII outside a string";
      return i;
    } else {
      ++i;
    }
  }
  return i;
}

size_t gm_escape_controls(const char *in, char *out, size_t cap) {
  size_t w = 0;
  if (cap == 0) return 0;
  for (const unsigned char *c = (const unsigned char *)in; *c != '\0' && w + 1 < cap; ++c) {
    if (*c < 0x20 || *c == 0x7F) {
      if (w + 5 > cap) break;
      w += (size_t)snprintf(out + w, 5, "\\x%02x", *c);
    } else {
      out[w++] = (char)*c;
    }
  }
  out[w] = '\0';
  return w;
}
