"""Imported last by the worker server (:data:`tyrelab.executor.WORKER_PRELOAD`): says its preload is done.

The server process inherits the environment variable
:data:`tyrelab.executor.READY_VARIABLE`, the path of a file to create; the parent waits for
that file before it asks the server for workers (see :func:`tyrelab.executor.worker_pool`).
"""

import os

__all__: list[str] = []

_path = os.environ.get("TYRELAB_WORKER_SERVER_READY")
if _path:
    try:
        with open(_path, "w", encoding="ascii") as _fh:
            _fh.write(str(os.getpid()))
    except OSError:  # the parent was interrupted and its temporary folder is gone: nobody waits
        pass
