"""The catalogue file format (defined once in :mod:`gyrovib.catalog.spec`), its YAML
dialect, validation into immutable records, located messages, the JSON Schema
and the bundled files. See docs/architecture.md, "Catalogue"."""
