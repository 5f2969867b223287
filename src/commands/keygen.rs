//! `rattleback keygen`: the key that signs recordings.

use crate::commands::failure::{Failure, Outcome};
use crate::record;

pub fn keygen(args: &crate::commands::cli::KeygenArgs) -> Outcome {
    match record::sign::keygen(&args.name) {
        Ok((secret, public)) => {
            say!(
                "{}: private key (mode 0600): record with --sign {}",
                secret.display(),
                secret.display()
            );
            say!(
                "{}: public key: verify with replay FILE --verify --key {}",
                public.display(),
                public.display()
            );
            Ok(())
        }
        Err(e) => Err(Failure::input(format!("keygen: {e}"))),
    }
}
