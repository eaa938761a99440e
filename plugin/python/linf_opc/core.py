"""Locates the compiled core (linf_opc_core), installed beside this package or on sys.path."""
try:
    from . import linf_opc_core as _core  # installed KLayout package
except ImportError:  # a checkout: the build directory is on sys.path
    import linf_opc_core as _core

voronoi_polygons = _core.voronoi_polygons
voronoi_sites = _core.voronoi_sites
gauges_polygons = _core.gauges_polygons
select_windows = _core.select_windows
cover_points = _core.cover_points
estimate_pitch = _core.estimate_pitch
farthest_voronoi = _core.farthest_voronoi
cgal_construction_seconds = _core.cgal_construction_seconds
DiagramError = _core.DiagramError
