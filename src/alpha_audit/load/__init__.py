"""Loaders: YAML themes, icon-set manifests, project config and SVG rasterisation."""
