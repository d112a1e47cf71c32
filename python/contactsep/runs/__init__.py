"""Run machinery below the studies: worker pools, the Dask backend, chunk
sizing, stop requests and the code digest.  It imports only the shared root
modules and :mod:`contactsep.output`."""
