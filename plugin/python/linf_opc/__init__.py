"""L-infinity Voronoi OPC analysis for KLayout: the editor's menu and the batch commands, both
calling the same stage functions and writers. The stages' contracts and rules are described in
docs/design.md.

Stages (plain data in and out; the work is done by the compiled core, core.py):
  diagram, gauges, selection, split, farthest; halves (Table 5.9's two-layouts experiment)
  flow        diagram -> gauges -> selection -> split on one layer, every output written
Readers:
  layout (a layer as flat polygons, polygons.py), glp (contest clips), markers, inputs (the
  layer a command works on)
Writers, one module per stage's outputs (result layouts through the core's writer, output.py):
  diagram_output, gauge_output, selection_output (and report.py, picture.py, report_db.py),
  split_output; staging (files moved into place when a command succeeds)
Batch:
  commands (the command table and main(), run by macros/linf_opc.py), arguments, runs
Editor:
  menu, dialogs, worker (the core in a watched child process)
"""
