#!/bin/sh
# docs/maxwell-mesh.md: `geomint maxwell mesh-cavity ARGS` as markdown: the level lines as a
# code block, the tables as tables, every other line a paragraph (scripts/docs_regen.py runs it).
geomint maxwell mesh-cavity "$@" | awk '
  /^level/ { if (!code) print ""; code = 1; print "    " $0; next }
  /^\|/    { if (!table) print ""; table = 1; code = 0; print; next }
  NF       { print ""; print; code = 0; table = 0 }
  !NF      { table = 0 }'
