//! Who may do what: anonymous clients read; the users of the users file
//! read and write, and log in only over an encrypted or signed channel
//! (Basic256Sha256), so that a password never crosses the network in
//! clear.

use super::users::Users;
use async_opcua::crypto::SecurityPolicy;
use async_opcua::server::address_space::AccessLevel;
use async_opcua::server::authenticator::{
    AuthManager, Password, UserToken, user_pass_security_policy_id,
};
use async_opcua::server::{ANONYMOUS_USER_TOKEN_ID, ServerEndpoint};
use async_opcua::types::{Error, NodeId, StatusCode, UAString, UserTokenPolicy, UserTokenType};

/// The policy id of anonymous logins.
const ANONYMOUS_POLICY: &str = "anonymous";

/// The server's authenticator.
pub(crate) struct PlcAuth {
    pub(crate) users: Users,
}

impl PlcAuth {
    /// Whether users may log in on `endpoint`: only on a secure channel.
    fn logins_on(&self, endpoint: &ServerEndpoint) -> bool {
        !self.users.is_empty() && endpoint.security_policy() != SecurityPolicy::None
    }
}

#[async_trait::async_trait]
impl AuthManager for PlcAuth {
    async fn authenticate_anonymous_token(&self, endpoint: &ServerEndpoint) -> Result<(), Error> {
        if endpoint.user_token_ids.contains(ANONYMOUS_USER_TOKEN_ID) {
            Ok(())
        } else {
            Err(Error::new(
                StatusCode::BadIdentityTokenRejected,
                "anonymous logins are not accepted here",
            ))
        }
    }

    async fn authenticate_username_identity_token(
        &self,
        endpoint: &ServerEndpoint,
        username: &str,
        password: &Password,
    ) -> Result<UserToken, Error> {
        if !self.logins_on(endpoint) {
            return Err(Error::new(
                StatusCode::BadIdentityTokenRejected,
                "user logins need a Basic256Sha256 endpoint",
            ));
        }
        if self.users.verify(username, password.get()) {
            Ok(UserToken(format!("user:{username}")))
        } else {
            Err(Error::new(
                StatusCode::BadUserAccessDenied,
                "unknown user or wrong password",
            ))
        }
    }

    fn effective_user_access_level(
        &self,
        token: &UserToken,
        user_access_level: AccessLevel,
        _node_id: &NodeId,
    ) -> AccessLevel {
        if token.is_anonymous() {
            user_access_level - AccessLevel::CURRENT_WRITE
        } else {
            user_access_level
        }
    }

    fn user_token_policies(&self, endpoint: &ServerEndpoint) -> Vec<UserTokenPolicy> {
        let mut policies = vec![UserTokenPolicy {
            policy_id: UAString::from(ANONYMOUS_POLICY),
            token_type: UserTokenType::Anonymous,
            issued_token_type: UAString::null(),
            issuer_endpoint_url: UAString::null(),
            security_policy_uri: UAString::null(),
        }];
        if self.logins_on(endpoint) {
            policies.push(UserTokenPolicy {
                policy_id: user_pass_security_policy_id(endpoint),
                token_type: UserTokenType::UserName,
                issued_token_type: UAString::null(),
                issuer_endpoint_url: UAString::null(),
                security_policy_uri: UAString::null(),
            });
        }
        policies
    }
}
