"""The thesis's general model, eq. (23): any contact points, any orthodox
end conditions, any number of modes, evaluated in batches."""
