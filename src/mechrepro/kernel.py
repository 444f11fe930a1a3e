"""An in-process IPython kernel for papermill: the notebook runs in the runner's process.

A kernel process costs each notebook job about a second (a second interpreter, ipykernel's
imports, the ZMQ handshake).  ipykernel's own in-process kernel avoids that but does not fit
nbclient 0.11 as shipped: it runs each request with ``run_sync``, which inside nbclient's
running event loop moves the cell onto a background thread, and its stdout/stderr never get
the request's parent header (the shell sets it on ``sys.stdout`` before the kernel swaps its
streams in), so nbclient drops printed output.  The subclasses below fix exactly that: the
cell is awaited on nbclient's loop (main thread, as in a kernel process) and the streams are
tagged and flushed before "idle", as a kernel process does.  One notebook per process (the
IPython shell is a singleton); tests/test_notebook.py checks a cell sees the same state
(warnings filters, rcParams, environment, cwd, sys.path) as in a kernel process.
"""
from __future__ import annotations

import sys

from ipykernel.inprocess.blocking import BlockingInProcessKernelClient
from ipykernel.inprocess.ipkernel import InProcessKernel
from ipykernel.inprocess.manager import InProcessKernelManager
from traitlets import DottedObjectName
from traitlets.config.loader import KVArgParseConfigLoader


class Kernel(InProcessKernel):
    def set_parent(self, ident, parent, channel="shell"):
        super().set_parent(ident, parent, channel)
        if channel == "shell":
            self.stdout.set_parent(parent)
            self.stderr.set_parent(parent)

    async def execute_request(self, stream, ident, parent):
        with self._redirected_io():
            await super(InProcessKernel, self).execute_request(stream, ident, parent)
            sys.stdout.flush()  # before "idle", as a kernel process flushes its streams
            sys.stderr.flush()


class Client(BlockingInProcessKernelClient):
    """Cells are awaited on the caller's (nbclient's) event loop, in its thread."""

    async def _execute(self, msg) -> str:
        stream = self.kernel.shell_stream
        self.session.send(stream, msg)
        await self.kernel.dispatch_shell(stream.recv_multipart())
        _idents, reply = self.session.recv(stream, copy=False)
        self.shell_channel.call_handlers(reply)
        return msg["header"]["msg_id"]

    def execute(self, code, silent=False, store_history=True, user_expressions=None,
                allow_stdin=None, stop_on_error=True):
        return self._execute(self.session.msg("execute_request", dict(
            code=code, silent=silent, store_history=store_history,
            user_expressions=user_expressions or {}, allow_stdin=False,
            stop_on_error=stop_on_error)))

    async def wait_for_ready(self, timeout=None):
        """Ready once constructed (the parent's check waits on timeouts)."""


class KernelManager(InProcessKernelManager):
    client_class = DottedObjectName("mechrepro.kernel.Client")

    def start_kernel(self, extra_arguments=(), **kwargs):
        # the command-line config a kernel process would get (nbclient: in-memory history)
        config = self.config.copy()
        config.merge(KVArgParseConfigLoader(list(extra_arguments)).load_config())
        self.kernel = Kernel(parent=self, session=self.session, config=config)

    def shutdown_kernel(self, now=False, restart=False):
        super().shutdown_kernel()
