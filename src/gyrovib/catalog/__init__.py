"""Catalogue files: their YAML dialect and guards (:mod:`~gyrovib.catalog.dialect`),
reading, validating through :mod:`gyrovib.models` and merging
(:mod:`~gyrovib.catalog.loader`), placing a path in a file
(:mod:`~gyrovib.catalog.locate`), pydantic's errors as located sentences
(:mod:`~gyrovib.catalog.messages`) and the one writer of the catalogue YAML gyrovib emits
(:mod:`~gyrovib.catalog.writer`). The format itself is :mod:`gyrovib.models`.
See docs/architecture.md, "Catalogue"."""
