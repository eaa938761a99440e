"""L-infinity Voronoi OPC analysis for KLayout.

The flow is a chain of stages with plain-data contracts (see README, "Flow stages"):
  layout.read_layer   KLayout layer   -> polygons (integer DBU)
  diagram.compute     polygons        -> Diagram (pieces with owners, clearances, kinds)
  output.*            Diagram         -> CSV, layout layers, summary
The editor actions (menu.py) and the batch macro (batch.py) call the same functions.
"""
