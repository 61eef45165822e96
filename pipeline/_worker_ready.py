"""Imported last by the worker server (:data:`tyrelab.executor.WORKER_PRELOAD`): says its preload is done.

It also freezes the objects the preload created (:func:`gc.freeze`).

The server process inherits the environment variable
:data:`tyrelab.executor.READY_VARIABLE`, the path of a file to create; the parent waits for
that file before it asks the server for workers (see :func:`tyrelab.executor.worker_pool`).
"""

import gc
import os

__all__: list[str] = []

# The preloaded modules stay alive in the server and every worker forked from it: out of the
# collector's sight, they are neither traversed by the workers' collections nor copied into
# them page by page when those collections touch their reference counts (see gc.freeze).
gc.freeze()

_path = os.environ.get("TYRELAB_WORKER_SERVER_READY")
if _path:
    try:
        with open(_path, "w", encoding="ascii") as _fh:
            _fh.write(str(os.getpid()))
    except OSError:  # the parent was interrupted and its temporary folder is gone: nobody waits
        pass
