# Sourced by the bench scripts whose summaries read KEY=value lines (ls_list_limit.sh,
# ls_fill_bound.sh): the awk functions they share, put in front of each program as
#   awk "$SUMMARY_AWK"'{ ... kv($0, "ls_cpu_s") ... }'
# shellcheck shell=bash disable=SC2034
SUMMARY_AWK='
  # KEY=value at the start of the line or after a space (so that "phi" does not read "phi_exact").
  function kv(line, key,   s) {
    if (match(line, "(^| )" key "=[^ ]+")) { s = substr(line, RSTART, RLENGTH); sub(/^ /, "", s); return substr(s, length(key) + 2) }
    return ""
  }
  # The sample standard deviation of m values from their sum s and sum of squares s2.
  function sd(s, s2, m,   v) { v = (m > 1) ? (s2 - s * s / m) / (m - 1) : 0; return v > 0 ? sqrt(v) : 0 }
'
