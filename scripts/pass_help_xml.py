#!/usr/bin/env python3
"""The built-in passes, as `voronoimesh passes` lists them, XML-escaped for the
ParaView filter's Pipeline documentation (paraview/plugin/filter/VoronoiMeshFilter.xml).
Passes from plugins are left out: the filter runs the built-in registry.

Usage: voronoimesh passes | pass_help_xml.py > passes.xml
"""
import sys
from xml.sax.saxutils import escape

blocks = sys.stdin.read().strip().split("\n\n")[1:]  # the first is the usage line
print("".join(escape(b) + "\n\n" for b in blocks if "[plugin " not in b.split("\n", 1)[0]), end="")
