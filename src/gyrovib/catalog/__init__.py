"""The catalogue file format: pydantic models, the YAML loader and the bundled files."""
