"""The ``bild-mdo`` command line (entry point :func:`bild_mdo.cli.main.main`)."""
