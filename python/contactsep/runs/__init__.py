"""Run machinery below the studies: worker pools, the Dask backend, chunk
sizing, stop requests, the code digest and the one journal of every
resumable command.  It imports only the shared root modules and
:mod:`contactsep.output`."""
